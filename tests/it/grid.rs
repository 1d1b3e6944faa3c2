//! Map loading and classification: every real map, every colour type, every bad input.

use crate::common::datasets;
use ksmcmc::grid::{pgm, Cell, Classifier, Grid, Limits, MapError, MapYaml, Mode, OccupancyMap};
use std::path::PathBuf;

/// The radish map and every Bormann image, or `None` (skip) without the datasets.
fn dataset_maps(test: &str) -> Option<Vec<PathBuf>> {
    let datasets = datasets(test)?;
    let mut maps = vec![datasets.join("radish/ubremen-cartesium.png")];
    let mut b: Vec<PathBuf> = std::fs::read_dir(datasets.join("bormann2016"))
        .expect("the datasets folder holds bormann2016/")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "png"))
        .collect();
    b.sort();
    maps.extend(b);
    Some(maps)
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("ksmcmc-grid-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Encodes a PNG of the given colour type and depth from 16-bit samples.
fn png_bytes(w: u32, h: u32, color: png::ColorType, depth: png::BitDepth, samples: &[u16]) -> Vec<u8> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, w, h);
        enc.set_color(color);
        enc.set_depth(depth);
        let mut wr = enc.write_header().unwrap();
        let data: Vec<u8> = match depth {
            png::BitDepth::Sixteen => samples.iter().flat_map(|s| s.to_be_bytes()).collect(),
            _ => samples.iter().map(|&s| s as u8).collect(),
        };
        wr.write_image_data(&data).unwrap();
    }
    out
}

#[test]
fn every_dataset_map_loads_with_all_three_classes() {
    let Some(maps) = dataset_maps("every_dataset_map_loads_with_all_three_classes") else { return };
    assert_eq!(maps.len(), 31, "radish map and 30 Bormann images expected");
    for path in maps {
        let m = OccupancyMap::load(&path, &Limits::default()).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let n = m.width() * m.height();
        let (f, u, o) = (m.count(Cell::Free), m.count(Cell::Unknown), m.count(Cell::Occupied));
        assert_eq!(f + u + o, n);
        // Every benchmark map has free space and walls; lab_ipa has no unknown (black outside).
        assert!(f > n / 20, "{}: only {f} free cells", path.display());
        assert!(o > 1000, "{}: only {o} occupied cells", path.display());
    }
}

#[test]
fn cartesium_unexplored_gray_is_unknown_not_free() {
    // The Radish map marks unexplored space with gray 230 (16-bit RGBA); it must not be free.
    let Some(datasets) = datasets("cartesium_unexplored_gray_is_unknown_not_free") else { return };
    let m = OccupancyMap::load(&datasets.join("radish/ubremen-cartesium.png"), &Limits::default()).unwrap();
    assert_eq!((m.width(), m.height()), (1237, 672));
    assert!(m.raster().alpha.is_some());
    let (f, u) = (m.count(Cell::Free), m.count(Cell::Unknown));
    assert!(u > 3 * f, "unexplored space dominates the Cartesium map: free {f}, unknown {u}");
    assert!(m.classified().at(0, 0) == &Cell::Unknown);
}

/// The fixture for the Cartesium test above, drawn here: a 16-bit RGBA map whose unexplored
/// outside is gray 230, around a walled room of white free space.
#[test]
fn unexplored_gray_230_in_16_bit_rgba_is_unknown_not_free() {
    let (w, h) = (40u32, 30u32);
    let mut samples = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let (inside, wall) =
                ((10..30).contains(&x) && (8..22).contains(&y), x == 10 || x == 29 || y == 8 || y == 21);
            let gray: u16 = if !inside {
                230
            } else if wall {
                0
            } else {
                255
            };
            samples.extend([gray * 257, gray * 257, gray * 257, 65535]);
        }
    }
    let m = OccupancyMap::from_bytes(&png_bytes(w, h, png::ColorType::Rgba, png::BitDepth::Sixteen, &samples)).unwrap();
    assert!(m.raster().alpha.is_some());
    let (f, u, o) = (m.count(Cell::Free), m.count(Cell::Unknown), m.count(Cell::Occupied));
    assert_eq!((f, o), (18 * 12, 2 * 20 + 2 * 12));
    assert_eq!(u, (w * h) as usize - f - o);
    assert!(m.classified().at(0, 0) == &Cell::Unknown);
}

#[test]
fn pgm_p2_and_p5_8_and_16_bit_agree() {
    let values8: [u8; 6] = [0, 50, 120, 205, 240, 255];
    let p2 = format!("P2\n# a comment\n3 2\n255\n{}\n", values8.map(|v| v.to_string()).join(" "));
    let p5 = pgm::encode_u8(3, 2, &values8);
    let values16: Vec<u16> = values8.iter().map(|&v| v as u16 * 257).collect();
    let p5_16 = pgm::encode_u16(3, 2, &values16);
    let p2_16 = format!("P2 3 2 65535 {}", values16.iter().map(|v| v.to_string()).collect::<Vec<_>>().join(" "));
    let expect = [Cell::Occupied, Cell::Occupied, Cell::Unknown, Cell::Unknown, Cell::Free, Cell::Free];
    for bytes in [p2.as_bytes(), &p5, &p5_16, p2_16.as_bytes()] {
        let m = OccupancyMap::from_bytes(bytes).unwrap();
        assert_eq!(m.classified().cells(), &expect);
        assert_eq!(m.raster().gray.at(5 % 3, 1), &65535);
    }
}

#[test]
fn pgm_with_small_maxval_is_scaled() {
    // maxval 15: 15 is white, 0 black, 8 is about 53 % gray (unknown).
    let m = OccupancyMap::from_bytes(b"P2 3 1 15 0 8 15").unwrap();
    assert_eq!(m.classified().cells(), &[Cell::Occupied, Cell::Unknown, Cell::Free]);
}

#[test]
fn png_every_colour_type_and_depth() {
    use png::{BitDepth::*, ColorType::*};
    let gray = [0u16, 128, 255, 255];
    let expect = [Cell::Occupied, Cell::Unknown, Cell::Free, Cell::Unknown];
    // Last pixel is transparent where there is alpha; otherwise it is made unknown by value.
    let cases: Vec<(png::ColorType, png::BitDepth, Vec<u16>)> = vec![
        (Grayscale, Eight, vec![0, 128, 255, 200]),
        (Grayscale, Sixteen, vec![0, 128 * 257, 65535, 200 * 257]),
        (GrayscaleAlpha, Eight, gray.iter().zip([255, 255, 255, 0]).flat_map(|(g, a)| [*g, a]).collect()),
        (GrayscaleAlpha, Sixteen, gray.iter().zip([65535, 65535, 65535, 0]).flat_map(|(g, a)| [*g * 257, a]).collect()),
        (Rgb, Eight, vec![0, 0, 0, 100, 128, 156, 255, 255, 255, 200, 200, 200]),
        (Rgb, Sixteen, vec![0, 0, 0, 128 * 257, 128 * 257, 128 * 257, 65535, 65535, 65535, 51400, 51400, 51400]),
        (Rgba, Eight, vec![0, 0, 0, 255, 128, 128, 128, 255, 255, 255, 255, 255, 255, 255, 255, 0]),
        (
            Rgba,
            Sixteen,
            vec![0, 0, 0, 65535, 32896, 32896, 32896, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 65535, 0],
        ),
    ];
    for (color, depth, samples) in cases {
        let bytes = png_bytes(2, 2, color, depth, &samples);
        let m = OccupancyMap::from_bytes(&bytes).unwrap_or_else(|e| panic!("{color:?} {depth:?}: {e}"));
        assert_eq!(m.classified().cells(), &expect, "{color:?} {depth:?}");
    }
}

#[test]
fn png_palette_and_one_bit_gray() {
    // 1-bit gray: 0 black, 1 white.
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, 8, 1);
        enc.set_color(png::ColorType::Grayscale);
        enc.set_depth(png::BitDepth::One);
        enc.write_header().unwrap().write_image_data(&[0b1010_0000]).unwrap();
    }
    let m = OccupancyMap::from_bytes(&out).unwrap();
    assert_eq!(&m.classified().cells()[..4], &[Cell::Free, Cell::Occupied, Cell::Free, Cell::Occupied]);
    // Palette: index 0 black, 1 white.
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, 2, 1);
        enc.set_color(png::ColorType::Indexed);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_palette(vec![0, 0, 0, 255, 255, 255]);
        enc.write_header().unwrap().write_image_data(&[1, 0]).unwrap();
    }
    let m = OccupancyMap::from_bytes(&out).unwrap();
    assert_eq!(m.classified().cells(), &[Cell::Free, Cell::Occupied]);
}

#[test]
fn ros_yaml_pair_round_trips_through_files() {
    let d = tmpdir("roundtrip");
    let cells = vec![Cell::Occupied, Cell::Free, Cell::Unknown, Cell::Free, Cell::Free, Cell::Occupied];
    let m = OccupancyMap::from_classified(Grid::from_vec(3, 2, cells.clone()).unwrap());
    std::fs::write(d.join("m.pgm"), m.to_pgm()).unwrap();
    std::fs::write(d.join("m.yaml"), m.to_yaml("m.pgm")).unwrap();
    let back = OccupancyMap::load(&d.join("m.yaml"), &Limits::default()).unwrap();
    assert_eq!(back.classified().cells(), &cells);
    assert_eq!(back.yaml().image, "m.pgm");
}

#[test]
fn ros_modes_negate_and_thresholds() {
    let img = pgm::encode_u8(4, 1, &[0, 100, 205, 254]);
    let yaml = |extra: &str| format!("image: m.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\n{extra}");
    let load = |extra: &str| OccupancyMap::from_yaml_and_image(&yaml(extra), &img, &Limits::default()).unwrap();
    use Cell::*;
    // trinary defaults: p = (255 - v)/255: 1.0 occ, 0.61 unknown, 0.196078 unknown, 0.004 free
    assert_eq!(load("").classified().cells(), &[Occupied, Unknown, Unknown, Free]);
    // negate: p = v/255
    assert_eq!(load("negate: 1\n").classified().cells(), &[Free, Unknown, Occupied, Occupied]);
    // raw: p = v/100, above 100 unknown
    assert_eq!(load("mode: raw\n").classified().cells(), &[Free, Occupied, Unknown, Unknown]);
    // lower occupied threshold makes 100 occupied
    assert_eq!(load("occupied_thresh: 0.5\n").classified().cells(), &[Occupied, Occupied, Unknown, Free]);
    let y = MapYaml::parse(&yaml("mode: scale  # graded\nfree_thresh: 0.25\n")).unwrap();
    assert_eq!((y.mode, y.free_thresh), (Mode::Scale, 0.25));
}

#[test]
fn yaml_errors_name_the_line() {
    let cases = [
        ("image: a.pgm\nresolution: fast\norigin: [0,0,0]\n", "line 2"),
        ("image: a.pgm\nresolution: 0.05\norigin: [0,0]\n", "three numbers"),
        ("image: a.pgm\nresolution: 0.05\n", "origin"),
        ("resolution: 0.05\norigin: [0,0,0]\n", "image"),
        ("image: a.pgm\nresolution: -1\norigin: [0,0,0]\n", "positive"),
        ("image: a.pgm\nresolution: 0.05\norigin: [0,0,0]\nmode: fancy\n", "trinary"),
        ("image: a.pgm\nresolution: 0.05\norigin: [0,0,0]\nnegate: maybe\n", "negate"),
        ("image: a.pgm\nresolution: 0.05\norigin: [0,0,0]\nfree_thresh: 0.9\n", "below"),
        ("image: a.pgm\nresolution: 0.05\norigin: [0,0,0]\noccupied_thresh: 2\n", "probability"),
        ("this is not yaml\n", "key: value"),
    ];
    for (text, needle) in cases {
        let e = MapYaml::parse(text).unwrap_err().to_string();
        assert!(e.contains(needle), "{text:?} gave {e:?}, wanted {needle:?}");
    }
}

#[test]
fn yaml_naming_a_missing_image_and_non_utf8_yaml() {
    let d = tmpdir("missing");
    std::fs::write(d.join("m.yaml"), "image: nowhere.pgm\nresolution: 0.05\norigin: [0,0,0]\n").unwrap();
    let e = OccupancyMap::load(&d.join("m.yaml"), &Limits::default()).unwrap_err();
    assert!(matches!(e, MapError::MissingImage { .. }), "{e:?}");
    assert!(e.to_string().contains("nowhere.pgm"));
    std::fs::write(d.join("bad.yaml"), b"image: \xff\xfe.pgm\n").unwrap();
    let e = OccupancyMap::load(&d.join("bad.yaml"), &Limits::default()).unwrap_err();
    assert!(matches!(e, MapError::NotUtf8 { offset: 7, .. }), "{e:?}");
}

#[test]
fn bad_images_are_errors_with_messages() {
    // A valid gray PNG of scattered map classes (it compresses poorly: well over 200 bytes) to
    // cut short and corrupt.
    let samples: Vec<u16> =
        (0..64 * 64u32).map(|i| [0, 205, 254][(i.wrapping_mul(2_654_435_761) >> 13) as usize % 3]).collect();
    let real = png_bytes(64, 64, png::ColorType::Grayscale, png::BitDepth::Eight, &samples);
    assert!(real.len() > 200 && OccupancyMap::from_bytes(&real).is_ok());
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("empty", vec![], "empty"),
        ("wrong magic", b"hello world".to_vec(), "not an occupancy map"),
        ("yaml given as image", b"image: m.pgm\n".to_vec(), "map.yaml"),
        ("colour ppm", b"P6 1 1 255 abc".to_vec(), "grayscale PGM"),
        ("zero width", b"P5\n0 10\n255\n".to_vec(), "0x10"),
        ("zero height", b"P2 10 0 255".to_vec(), "10x0"),
        ("absurd", b"P5\n100000 100000\n255\n".to_vec(), "over the limit"),
        ("overflowing digits", b"P5\n99999999999999999999999 2\n255\n".to_vec(), "over the limit"),
        ("maxval 0", b"P5 2 2 0\n\0\0\0\0".to_vec(), "maximum value"),
        ("maxval too big", b"P5 2 2 70000\n".to_vec(), "maximum value"),
        ("truncated P5", b"P5 4 4 255\nabc".to_vec(), "truncated"),
        ("truncated P2", b"P2 4 4 255\n1 2 3".to_vec(), "truncated"),
        ("header cut", b"P5 4".to_vec(), "height"),
        ("sample over maxval", b"P2 2 1 10 5 11".to_vec(), "above"),
        ("garbage sample", b"P2 2 1 10 5 x".to_vec(), "'x'"),
        ("truncated png", real[..100].to_vec(), "PNG"),
        ("png header only", real[..33].to_vec(), "PNG"),
        (
            "corrupt png",
            {
                let mut c = real.clone();
                for b in &mut c[60..200] {
                    *b ^= 0x5a;
                }
                c
            },
            "PNG",
        ),
    ];
    for (name, bytes, needle) in cases {
        let e = OccupancyMap::from_bytes(&bytes).expect_err(name);
        assert!(e.to_string().contains(needle), "{name}: {e}");
    }
}

#[test]
fn limits_are_checked_before_allocating() {
    let small = Limits { max_cells: 100 };
    let e =
        OccupancyMap::from_image_bytes(&pgm::encode_u8(11, 10, &[0; 110]), Classifier::default(), &small).unwrap_err();
    assert!(matches!(e, MapError::TooLarge { width: 11, height: 10, limit: 100 }));
    // A PNG whose header claims 2^31 x 2^31 fails on the header, not on a huge allocation.
    let mut p = png_bytes(1, 1, png::ColorType::Grayscale, png::BitDepth::Eight, &[0]);
    p[16..20].copy_from_slice(&0x7fff_ffffu32.to_be_bytes());
    p[20..24].copy_from_slice(&0x7fff_ffffu32.to_be_bytes());
    assert!(OccupancyMap::from_bytes(&p).is_err());
}

#[test]
fn classifier_thresholds_are_validated() {
    let m = OccupancyMap::from_bytes(b"P2 1 1 255 0").unwrap();
    for c in [
        Classifier::Intensity { occupied_max: f64::NAN, unknown_max: 0.9 },
        Classifier::Intensity { occupied_max: 0.5, unknown_max: 0.4 },
        Classifier::Intensity { occupied_max: -0.1, unknown_max: 0.4 },
        Classifier::MapServer { negate: false, occupied_thresh: 0.1, free_thresh: 0.5, mode: Mode::Trinary },
    ] {
        assert!(m.clone().set_classifier(c).is_err(), "{c:?}");
    }
    let mut m2 = m.clone();
    m2.set_classifier(Classifier::Intensity { occupied_max: 0.0, unknown_max: 0.5 }).unwrap();
    assert_eq!(m2.classified().cells(), &[Cell::Occupied]);
}

#[test]
fn fuzzed_headers_never_panic() {
    // Deterministic mutation of valid files: every result is Ok or Err, never a panic.
    let seeds: Vec<Vec<u8>> = vec![
        b"P2 3 2 255\n0 1 2 3 4 5\n".to_vec(),
        pgm::encode_u16(3, 2, &[0, 1, 2, 3, 4, 5]),
        png_bytes(3, 2, png::ColorType::Rgba, png::BitDepth::Eight, &[7; 24]),
    ];
    let mut state = 0x2545_f491_4f6c_dd1du64;
    for seed in &seeds {
        for _ in 0..3000 {
            let mut b = seed.clone();
            for _ in 0..3 {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                let i = (state % b.len() as u64) as usize;
                b[i] = (state >> 32) as u8;
            }
            state ^= state << 13;
            let cut = (state >> 40) as usize % (b.len() + 1);
            let _ = OccupancyMap::from_bytes(&b);
            let _ = OccupancyMap::from_bytes(&b[..cut]);
        }
    }
}

/// Maps drawn without an unknown class paint everything outside the building black. The map
/// keeps a wall's depth of it occupied (0.6 m: 12 cells at 5 cm, 6 at 10 cm) and calls the rest
/// unknown, whichever way the map was made.
#[test]
fn the_inside_of_a_solid_mass_is_unknown_in_every_map() {
    let (w, h) = (60usize, 40usize);
    let room = |x: usize, y: usize| (25..35).contains(&x) && (15..25).contains(&y);
    let pixels: Vec<u8> = (0..w * h).map(|i| if room(i % w, i / w) { 255 } else { 0 }).collect();
    let map = OccupancyMap::from_bytes(&pgm::encode_u8(w, h, &pixels)).unwrap();
    let c = map.classified();
    assert_eq!(*c.at(24, 20), Cell::Occupied, "a wall face stays");
    assert_eq!(*c.at(13, 20), Cell::Occupied, "12 cells deep stays");
    assert_eq!(*c.at(12, 20), Cell::Unknown, "13 cells deep is hidden");
    assert_eq!(*c.at(0, 0), Cell::Unknown);
    // A map made from classes is hidden the same way, and again for its own resolution.
    let raw = map.classifier().classify_raster(map.raster());
    let painted = OccupancyMap::from_classified(raw);
    assert_eq!(painted.classified(), c);
    let coarse = painted.with_yaml(MapYaml { resolution: 0.1, ..map.yaml().clone() });
    assert_eq!(*coarse.classified().at(19, 20), Cell::Occupied, "6 cells deep stays at 10 cm");
    assert_eq!(*coarse.classified().at(18, 20), Cell::Unknown);
}
