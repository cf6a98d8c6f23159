//! `texplore probe`.

use crate::probe::{ProbeFormat, make_probe};
use anyhow::Result;
use std::path::PathBuf;

/// `texplore probe`.
#[derive(Debug, clap::Args)]
pub struct ProbeArgs {
    /// Equirectangular panorama (HDR or LDR; left edge longitude -180, top row the zenith).
    pub panorama: PathBuf,
    /// Output probe image in the format its extension names (.hdr or .exr keep HDR values;
    /// .png, .jpg, .tif and .ppm clip); checked before the panorama is read.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Width and height of the probe in pixels.
    #[arg(long, default_value_t = 512, value_parser = super::parse_resolution)]
    pub size: u32,
    /// Probe layout.
    #[arg(long, value_enum, default_value_t = ProbeFormat::Angular)]
    pub format: ProbeFormat,
}

/// Converts the panorama and says where the probe went.
///
/// # Errors
/// The panorama cannot be read or the probe written.
pub fn run(a: &ProbeArgs) -> Result<()> {
    make_probe(&a.panorama, &a.output, a.size, a.format)?;
    eprintln!(
        "wrote {} ({size}x{size}, {:?})",
        a.output.display(),
        a.format,
        size = a.size
    );
    Ok(())
}
