//! Netpbm grayscale maps: P2 (plain text) and P5 (binary), 8 and 16 bits.
//!
//! PGM is what ROS map_server, gmapping and slam_toolbox write. The reader checks the declared
//! size against [`Limits`] *before* allocating anything, so a hostile header cannot make it
//! reserve gigabytes, and it checks that the file really holds the samples it promises.

use super::error::MapError;
use super::raster::{Grid, Raster};
use super::Limits;

/// Decodes a P2 or P5 PGM into a 16-bit raster.
pub fn decode(bytes: &[u8], limits: &Limits) -> Result<Raster, MapError> {
    let mut p = Parser { bytes, pos: 0 };
    let magic = p.take(2);
    let binary = match magic {
        b"P5" => true,
        b"P2" => false,
        _ => return Err(MapError::BadPgmHeader { message: "the file does not start with P2 or P5".into() }),
    };
    let width = p.header_number("width")?;
    let height = p.header_number("height")?;
    let maxval = p.header_number("maximum value")?;
    if !(1..=65535).contains(&maxval) {
        return Err(MapError::BadPgmHeader { message: format!("maximum value {maxval} is outside 1..=65535") });
    }
    let (w, h) = limits.check(width, height)?;
    let n = w * h;
    let scale = |v: u32| -> u16 { ((v as u64 * 65535 + maxval / 2) / maxval) as u16 };
    let mut cells = Vec::new();
    if binary {
        // Exactly one whitespace byte separates the header from the samples.
        if !p.at_end() {
            if !p.peek().is_ascii_whitespace() {
                return Err(MapError::BadPgmHeader {
                    message: "expected one whitespace byte after the maximum value".into(),
                });
            }
            p.pos += 1;
        }
        let bytes_per = if maxval < 256 { 1 } else { 2 };
        let data = &bytes[p.pos..];
        if data.len() < n * bytes_per {
            return Err(MapError::Truncated { format: "PGM", expected: n, found: data.len() / bytes_per });
        }
        cells.reserve_exact(n);
        for i in 0..n {
            let v =
                if bytes_per == 1 { data[i] as u32 } else { u16::from_be_bytes([data[2 * i], data[2 * i + 1]]) as u32 };
            if v as u64 > maxval {
                return Err(MapError::SampleOutOfRange { index: i, value: v, maxval: maxval as u32 });
            }
            cells.push(scale(v));
        }
    } else {
        // Each plain sample takes at least two bytes ("0 "), which bounds the allocation by
        // the input size rather than the header.
        cells.reserve(n.min(bytes.len() / 2 + 1));
        for i in 0..n {
            match p.number()? {
                Some(v) if v <= maxval => cells.push(scale(v as u32)),
                Some(v) => {
                    return Err(MapError::SampleOutOfRange {
                        index: i,
                        value: v.min(u32::MAX as u64) as u32,
                        maxval: maxval as u32,
                    })
                }
                None => return Err(MapError::Truncated { format: "PGM", expected: n, found: i }),
            }
        }
    }
    let gray = Grid::from_vec(w, h, cells).expect("sample count checked above");
    Ok(Raster { gray, alpha: None })
}

/// Encodes 8-bit samples as a binary (P5) PGM.
pub fn encode_u8(width: usize, height: usize, samples: &[u8]) -> Vec<u8> {
    debug_assert_eq!(samples.len(), width * height);
    let mut out = format!("P5\n{width} {height}\n255\n").into_bytes();
    out.extend_from_slice(samples);
    out
}

/// Encodes 16-bit samples as a binary (P5) PGM with maximum value 65535, big-endian as the
/// format requires.
pub fn encode_u16(width: usize, height: usize, samples: &[u16]) -> Vec<u8> {
    debug_assert_eq!(samples.len(), width * height);
    let mut out = format!("P5\n{width} {height}\n65535\n").into_bytes();
    out.reserve(samples.len() * 2);
    for s in samples {
        out.extend_from_slice(&s.to_be_bytes());
    }
    out
}

struct Parser<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl Parser<'_> {
    fn take(&mut self, n: usize) -> &[u8] {
        let end = (self.pos + n).min(self.bytes.len());
        let s = &self.bytes[self.pos..end];
        self.pos = end;
        s
    }

    fn at_end(&self) -> bool {
        self.pos >= self.bytes.len()
    }

    fn peek(&self) -> u8 {
        self.bytes[self.pos]
    }

    fn skip_space_and_comments(&mut self) {
        while !self.at_end() {
            let b = self.peek();
            if b == b'#' {
                while !self.at_end() && self.peek() != b'\n' && self.peek() != b'\r' {
                    self.pos += 1;
                }
            } else if b.is_ascii_whitespace() {
                self.pos += 1;
            } else {
                break;
            }
        }
    }

    /// Reads one unsigned decimal; `Ok(None)` at the end of the data.
    fn number(&mut self) -> Result<Option<u64>, MapError> {
        self.skip_space_and_comments();
        if self.at_end() {
            return Ok(None);
        }
        let start = self.pos;
        let mut v: u64 = 0;
        while !self.at_end() && self.peek().is_ascii_digit() {
            v = v.saturating_mul(10).saturating_add((self.peek() - b'0') as u64);
            self.pos += 1;
        }
        if self.pos == start {
            let c = self.peek();
            return Err(MapError::BadPgmHeader {
                message: format!(
                    "expected a decimal number at byte {start}, found {}",
                    if c.is_ascii_graphic() { format!("'{}'", c as char) } else { format!("byte 0x{c:02x}") }
                ),
            });
        }
        Ok(Some(v))
    }

    fn header_number(&mut self, what: &str) -> Result<u64, MapError> {
        match self.number()? {
            Some(v) => Ok(v),
            None => {
                Err(MapError::BadPgmHeader { message: format!("the file ends before the header gives the {what}") })
            }
        }
    }
}
