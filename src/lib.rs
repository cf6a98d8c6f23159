//! texplore: an interactive texture-mapping explorer built on a progressive CPU ray tracer.
//!
//! The path of a ray: [`camera`] makes it (with differentials), [`scene::Scene::hit`] finds the
//! nearest [`geometry`] hit in the object's generic space, a [`mapping`] turns the local hit
//! point into (u, v) with analytic derivatives, a [`texture`] filters texels, a [`material`]
//! shades with the [`scene`]'s lights, and the [`render`] film accumulates the samples that a
//! [`sampler`] placed.

pub mod camera;
// The command line (and its `bench`) has no meaning in a page.
#[cfg(not(target_arch = "wasm32"))]
pub mod cli;
pub mod coverage;
pub mod error;
pub mod field;
pub mod geometry;
pub mod input;
pub mod inspect;
pub mod lesson;
pub mod link;
pub mod mapping;
pub mod material;
pub mod math;
pub mod meshio;
pub mod names;
pub mod output;
pub mod probe;
pub mod render;
pub mod report;
pub mod robustness;
pub mod sampler;
pub mod scene;
pub mod shipped;
pub mod snapshot;
pub mod texture;

#[cfg(feature = "gui")]
pub mod gui;

pub use error::{Error, Result};
