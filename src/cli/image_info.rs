//! `texplore image-info`: what texplore reads from an image file, before using it as a texture.

use crate::texture::{ImageRequest, Texels, load_image, load_opened};
use anyhow::Result;
use std::path::PathBuf;
use std::time::Instant;

/// `texplore image-info`.
#[derive(Debug, clap::Args)]
pub struct ImageInfoArgs {
    /// An image file (PNG, JPEG, TIFF, PPM/PGM, Radiance HDR, OpenEXR).
    pub file: PathBuf,
    /// Print JSON (keys `width`, `height`, `storage`, `bytes`, ...).
    #[arg(long)]
    pub json: bool,
    /// Read the alpha channel (as a clip map's `Alpha` reads it) instead of the colour.
    #[arg(long)]
    pub alpha: bool,
    /// Write the texels as texplore holds them: `.exr` or `.hdr` as linear floats (exactly, for
    /// comparing with another decoder), `.png` as 8-bit sRGB. Checked before the image is read.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// Reads the image as a texture is read and prints its size and storage.
///
/// # Errors
/// The image is refused (the message names the file and the problem), or the output cannot be
/// written.
pub fn run(a: &ImageInfoArgs) -> Result<()> {
    if let Some(out) = &a.output {
        let mut exts = crate::output::LINEAR_EXTS.to_vec();
        exts.push("png");
        crate::output::check_output(out, &exts, &[&a.file])?;
    }
    let t0 = Instant::now();
    let img = if a.alpha {
        let file = crate::input::open_input(&a.file)?;
        load_opened(file, &a.file, ImageRequest::alpha())?.0
    } else {
        load_image(&a.file, true)?
    };
    let read = t0.elapsed();
    let (w, h) = (img.width(), img.height());
    let storage = match img.texels() {
        Texels::Srgb8(_) => "srgb8",
        Texels::Unorm8(_) => "unorm8",
        Texels::Linear(_) => "linear",
    };
    let bytes = img.texels_bytes();
    if let Some(out) = &a.output {
        if crate::output::extension(out) == "png" {
            crate::texture::save_png_checked(out, &[&a.file], w, h, &img.to_srgb8(), &[])?;
        } else {
            let mut rgb = Vec::with_capacity(w as usize * h as usize * 3);
            for row in 0..h {
                for column in 0..w {
                    rgb.extend(img.texel_top(column, row).to_array());
                }
            }
            crate::output::write_linear_image(out, &[&a.file], w, h, &rgb)?;
        }
    }
    if a.json {
        let v = serde_json::json!({
            "file": a.file.display().to_string(),
            "width": w,
            "height": h,
            "storage": storage,
            "bytes_per_texel": img.bytes_per_texel(),
            "bytes": bytes,
            "read_ms": read.as_secs_f64() * 1e3,
        });
        println!("{}", serde_json::to_string_pretty(&v)?);
        return Ok(());
    }
    println!("{}", a.file.display());
    println!("  size     {w} x {h} texels");
    println!(
        "  storage  {} ({} bytes a texel, {} in all, tiles included)",
        if storage == "srgb8" {
            "8-bit sRGB"
        } else {
            "linear float RGB"
        },
        img.bytes_per_texel(),
        crate::input::human_bytes(bytes)
    );
    println!("  time     read {:.1} ms", read.as_secs_f64() * 1e3);
    if let Some(out) = &a.output {
        println!("  wrote    {}", out.display());
    }
    Ok(())
}
