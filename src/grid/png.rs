//! PNG maps in every colour type: gray, gray+alpha, RGB, RGBA, palette; 1 to 16 bits.
//!
//! Map editors and benchmark sets save maps however their tool of the day did, so the loader
//! takes them all and reduces them to gray plus optional alpha (see [`Raster`]).

use super::error::MapError;
use super::raster::{Grid, Raster};
use super::Limits;

/// Decodes a PNG into a 16-bit raster. The size is checked against `limits` before the pixel
/// buffer is allocated.
pub fn decode(bytes: &[u8], limits: &Limits) -> Result<Raster, MapError> {
    let mut decoder = png::Decoder::new_with_limits(bytes, png::Limits { bytes: limits.max_cells.saturating_mul(8) });
    // Expand palettes and low bit depths to 8 bits and tRNS chunks to an alpha channel.
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(png_error)?;
    let (width, height) = {
        let info = reader.info();
        (info.width as u64, info.height as u64)
    };
    let (w, h) = limits.check(width, height)?;
    let mut buf = vec![0u8; reader.output_buffer_size()];
    let frame = reader.next_frame(&mut buf).map_err(png_error)?;
    let (color, depth) = reader.output_color_type();
    let channels = color.samples();
    let sixteen = depth == png::BitDepth::Sixteen;
    let bytes_per_sample = if sixteen { 2 } else { 1 };
    let line = frame.line_size;
    let sample = |row: &[u8], i: usize| -> u16 {
        if sixteen {
            u16::from_be_bytes([row[2 * i], row[2 * i + 1]])
        } else {
            row[i] as u16 * 257
        }
    };
    let (has_color, has_alpha) = match color {
        png::ColorType::Grayscale => (false, false),
        png::ColorType::GrayscaleAlpha => (false, true),
        png::ColorType::Rgb => (true, false),
        png::ColorType::Rgba => (true, true),
        png::ColorType::Indexed => return Err(MapError::Png { message: "palette was not expanded".into() }),
    };
    let mut gray = Vec::with_capacity(w * h);
    let mut alpha = has_alpha.then(|| Vec::with_capacity(w * h));
    for y in 0..h {
        let row = &buf[y * line..y * line + w * channels * bytes_per_sample];
        for x in 0..w {
            let base = x * channels;
            let g = if has_color {
                let sum = sample(row, base) as u32 + sample(row, base + 1) as u32 + sample(row, base + 2) as u32;
                ((sum + 1) / 3) as u16
            } else {
                sample(row, base)
            };
            gray.push(g);
            if let Some(a) = alpha.as_mut() {
                a.push(sample(row, base + channels - 1));
            }
        }
    }
    Ok(Raster {
        gray: Grid::from_vec(w, h, gray).expect("sized above"),
        alpha: alpha.map(|a| Grid::from_vec(w, h, a).expect("sized above")),
    })
}

fn png_error(e: png::DecodingError) -> MapError {
    match e {
        png::DecodingError::IoError(io) if io.kind() == std::io::ErrorKind::UnexpectedEof => {
            MapError::Png { message: "the file ends in the middle of the image data (truncated?)".into() }
        }
        png::DecodingError::LimitsExceeded => {
            MapError::Png { message: "the decoded image would exceed the memory limit for maps".into() }
        }
        other => MapError::Png { message: other.to_string() },
    }
}
