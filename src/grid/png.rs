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
    struct ToRaster {
        gray: Vec<u16>,
        alpha: Option<Vec<u16>>,
    }
    impl Pixels for ToRaster {
        fn start(&mut self, width: usize, height: usize, has_alpha: bool) {
            self.gray.reserve_exact(width * height);
            self.alpha = has_alpha.then(|| Vec::with_capacity(width * height));
        }
        fn pixel(&mut self, colour: &[u16], alpha: Option<u16>) {
            self.gray.push(match *colour {
                [r, g, b] => ((r as u32 + g as u32 + b as u32 + 1) / 3) as u16,
                _ => colour[0],
            });
            if let (Some(all), Some(a)) = (self.alpha.as_mut(), alpha) {
                all.push(a);
            }
        }
    }
    let mut sink = ToRaster { gray: Vec::new(), alpha: None };
    let (w, h) = decode_pixels(bytes, limits, &mut sink)?;
    Ok(Raster {
        gray: Grid::from_vec(w, h, sink.gray).expect("sized above"),
        alpha: sink.alpha.map(|a| Grid::from_vec(w, h, a).expect("sized above")),
    })
}

/// The cells of a PNG whose every colour channel is at least 250 of 255 (its 8 most
/// significant bits, for 16-bit images); alpha is ignored. See [`super::white_cells`].
pub(super) fn white(bytes: &[u8], limits: &Limits) -> Result<Grid<bool>, MapError> {
    struct White(Vec<bool>);
    impl Pixels for White {
        fn start(&mut self, width: usize, height: usize, _: bool) {
            self.0.reserve_exact(width * height);
        }
        fn pixel(&mut self, colour: &[u16], _: Option<u16>) {
            self.0.push(colour.iter().all(|&v| v >> 8 >= 250));
        }
    }
    let mut sink = White(Vec::new());
    let (w, h) = decode_pixels(bytes, limits, &mut sink)?;
    Ok(Grid::from_vec(w, h, sink.0).expect("sized above"))
}

/// What receives a PNG's pixels, row-major from the top-left.
trait Pixels {
    /// Called once, before the first pixel.
    fn start(&mut self, width: usize, height: usize, has_alpha: bool);
    /// One pixel: its colour samples (1 for gray, 3 for RGB) and alpha, 16 bits each (8-bit
    /// samples scaled by 257).
    fn pixel(&mut self, colour: &[u16], alpha: Option<u16>);
}

/// The one PNG decoding path: every colour type and depth, palettes and tRNS expanded, the
/// size checked against `limits` before the pixel buffer is allocated. Returns the size.
fn decode_pixels(bytes: &[u8], limits: &Limits, sink: &mut impl Pixels) -> Result<(usize, usize), MapError> {
    let mut decoder = png::Decoder::new_with_limits(bytes, png::Limits { bytes: limits.max_cells.saturating_mul(8) });
    // Expand palettes and low bit depths to 8 bits and tRNS chunks to an alpha channel.
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(png_error)?;
    let (width, height) = {
        let info = reader.info();
        // png 0.17 indexes the palette three bytes at a time when it expands it: a PLTE chunk
        // whose length is not a multiple of 3 panics there (found by `fuzz/` target png).
        if let Some(p) = info.palette.as_ref().filter(|p| p.is_empty() || p.len() % 3 != 0) {
            return Err(MapError::Png {
                message: format!(
                    "its palette (PLTE chunk) is {} bytes long, not a whole number of RGB entries",
                    p.len()
                ),
            });
        }
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
    let (colours, has_alpha) = match color {
        png::ColorType::Grayscale => (1, false),
        png::ColorType::GrayscaleAlpha => (1, true),
        png::ColorType::Rgb => (3, false),
        png::ColorType::Rgba => (3, true),
        png::ColorType::Indexed => return Err(MapError::Png { message: "palette was not expanded".into() }),
    };
    sink.start(w, h, has_alpha);
    let mut colour = [0u16; 3];
    for y in 0..h {
        let row = &buf[y * line..y * line + w * channels * bytes_per_sample];
        for x in 0..w {
            let base = x * channels;
            for (c, v) in colour[..colours].iter_mut().enumerate() {
                *v = sample(row, base + c);
            }
            sink.pixel(&colour[..colours], has_alpha.then(|| sample(row, base + channels - 1)));
        }
    }
    Ok((w, h))
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

#[cfg(test)]
mod tests {
    use super::*;

    fn encode(width: u32, colour: png::ColorType, depth: png::BitDepth, data: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut e = png::Encoder::new(&mut out, width, 1);
        e.set_color(colour);
        e.set_depth(depth);
        e.write_header().unwrap().write_image_data(data).unwrap();
        out
    }

    #[test]
    fn white_means_every_colour_channel_at_least_250() {
        let rgb = encode(3, png::ColorType::Rgb, png::BitDepth::Eight, &[255, 255, 255, 255, 255, 249, 250, 250, 250]);
        assert_eq!(white(&rgb, &Limits::default()).unwrap().cells(), &[true, false, true]);
        // The gray mean of (255, 255, 249) is 253: the raster alone could not tell.
        assert_eq!(decode(&rgb, &Limits::default()).unwrap().gray.cells()[1], 253 * 257);
        let gray16 = encode(2, png::ColorType::Grayscale, png::BitDepth::Sixteen, &[0xFA, 0x00, 0xF9, 0xFF]);
        assert_eq!(white(&gray16, &Limits::default()).unwrap().cells(), &[true, false]);
        let rgba = encode(1, png::ColorType::Rgba, png::BitDepth::Eight, &[255, 255, 255, 0]);
        assert_eq!(white(&rgba, &Limits::default()).unwrap().cells(), &[true], "alpha is ignored");
        assert_eq!(decode(&rgba, &Limits::default()).unwrap().alpha.unwrap().cells(), &[0]);
    }
}
