//! Occupancy grids: loading, classification (eq. 3.7) and writing.
//!
//! A map arrives as a PGM (P2 or P5, 8 or 16 bits), a PNG of any colour type, or a ROS
//! map_server pair (`map.yaml` naming the image). Loading decodes it to a gray [`Raster`],
//! then a [`Classifier`] turns every pixel into a [`Cell`]: occupied, unknown or free. Plain
//! images use the intensity thresholds of eq. 3.7 ([`Classifier::default`]); a `map.yaml` brings
//! map_server's own rule and thresholds.
//!
//! Nothing here trusts the input: sizes are checked against [`Limits`] before any pixel buffer
//! is allocated, and every failure is a [`MapError`] that says what to fix.
//!
//! ```
//! use ksmcmc::grid::{Cell, OccupancyMap};
//!
//! let map = OccupancyMap::from_bytes(b"P2\n2 2\n255\n0 255\n205 255\n").unwrap();
//! assert_eq!(map.classified().at(0, 0), &Cell::Occupied);
//! assert_eq!(map.classified().at(0, 1), &Cell::Unknown);
//! assert_eq!(map.count(Cell::Free), 2);
//!
//! // Bad input is an error with a message, never a panic.
//! let err = OccupancyMap::from_bytes(b"P5\n0 10\n255\n").unwrap_err();
//! assert!(err.to_string().contains("0x10"));
//! ```

mod classify;
mod error;
pub mod flood;
pub mod hidden;
pub mod morphology;
pub mod pgm;
pub mod png;
mod raster;
mod ros;

pub use classify::{Cell, Classifier};

/// The cell of the benchmark maps, 5 cm: the metres per cell of a map that does not say
/// (`MapYaml::for_image`'s default, a chain on a bare grid).
pub const BENCHMARK_CELL_M: f64 = 0.05;

/// The metres per cell that turn a length into cells: `resolution`, or
/// [`BENCHMARK_CELL_M`] where it is not a positive number.
pub fn cell_size_m(resolution: f64) -> f64 {
    if resolution.is_finite() && resolution > 0.0 {
        resolution
    } else {
        BENCHMARK_CELL_M
    }
}

/// `m` metres in whole cells of `resolution` metres ([`cell_size_m`]): the nearest whole
/// number, halves up, with the quotient's float noise forgiven (0.15 m is two 10 cm cells).
pub(crate) fn whole_cells(m: f64, resolution: f64) -> f64 {
    libm::round(m / cell_size_m(resolution) + 1e-9)
}
pub use error::MapError;
pub use raster::{Grid, Raster};
pub use ros::{MapYaml, Mode, MAX_YAML_BYTES};

use error::describe_start;

/// Resource limits for loading maps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// The largest number of cells a map may have. The default, 2^25 (about 33.5 million,
    /// e.g. 8192 x 4096), covers building-scale maps at 5 cm with room to spare while keeping
    /// a hostile header from asking for gigabytes (a map costs about 3 bytes per cell).
    pub max_cells: usize,
}

/// The default cell limit; see [`Limits::max_cells`].
pub const DEFAULT_MAX_CELLS: usize = 1 << 25;

impl Default for Limits {
    fn default() -> Self {
        Limits { max_cells: DEFAULT_MAX_CELLS }
    }
}

impl Limits {
    /// Checks a declared size, returning it as `usize`s.
    pub fn check(&self, width: u64, height: u64) -> Result<(usize, usize), MapError> {
        if width == 0 || height == 0 {
            return Err(MapError::Empty { width, height });
        }
        let cells = (width as u128) * (height as u128);
        if cells > self.max_cells as u128 {
            return Err(MapError::TooLarge { width, height, limit: self.max_cells });
        }
        Ok((width as usize, height as usize))
    }
}

/// The image formats a map can arrive in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// Netpbm gray map, P2 or P5.
    Pgm,
    /// Portable Network Graphics.
    Png,
}

impl ImageFormat {
    /// Recognises the format from the first bytes.
    pub fn sniff(bytes: &[u8]) -> Result<ImageFormat, MapError> {
        if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
            return Ok(ImageFormat::Png);
        }
        if bytes.len() >= 2 && (bytes.starts_with(b"P5") || bytes.starts_with(b"P2")) {
            return Ok(ImageFormat::Pgm);
        }
        if bytes.len() >= 2 && bytes[0] == b'P' && matches!(bytes[1], b'1' | b'3' | b'4' | b'6') {
            return Err(MapError::UnknownFormat {
                start: format!(
                    "{} (a Netpbm bitmap or colour image; save the map as a grayscale PGM or as PNG)",
                    describe_start(bytes)
                ),
            });
        }
        if let Ok(text) = std::str::from_utf8(&bytes[..bytes.len().min(4096)]) {
            if text.lines().any(|l| l.trim_start().starts_with("image:")) {
                return Err(MapError::UnknownFormat {
                    start: format!(
                        "{} (this is a map.yaml: load it together with the image it names)",
                        describe_start(bytes)
                    ),
                });
            }
        }
        Err(MapError::UnknownFormat { start: describe_start(bytes) })
    }
}

/// Decodes a PGM or PNG into a raster, whichever the bytes are.
pub fn decode_image(bytes: &[u8], limits: &Limits) -> Result<Raster, MapError> {
    match ImageFormat::sniff(bytes)? {
        ImageFormat::Pgm => pgm::decode(bytes, limits),
        ImageFormat::Png => png::decode(bytes, limits),
    }
}

/// The white cells of an image, as the room-segmentation benchmark (Bormann et al. 2016) marks
/// its truth regions: in a PNG every colour channel at least 250 of 255 (alpha ignored), in a
/// gray image a gray level of at least 250/255.
///
/// ```
/// let pgm = b"P2 3 1 255\n255 250 249\n";
/// let white = ksmcmc::grid::white_cells(pgm, &Default::default()).unwrap();
/// assert_eq!(white.cells(), &[true, true, false]);
/// assert!(ksmcmc::grid::white_cells(b"nope", &Default::default()).is_err());
/// ```
pub fn white_cells(bytes: &[u8], limits: &Limits) -> Result<Grid<bool>, MapError> {
    if ImageFormat::sniff(bytes)? == ImageFormat::Png {
        return png::white(bytes, limits);
    }
    Ok(decode_image(bytes, limits)?.gray.map(|&g| g >= 250 * 257))
}

/// Every pixel of `raster` through `classifier`, then the inside of solid occupied masses
/// hidden for a map of `resolution` metres per cell.
fn classify(raster: &Raster, classifier: &Classifier, resolution: f64) -> Grid<Cell> {
    hidden::hide_interior(&classifier.classify_raster(raster), hidden::depth_cells(resolution))
}

/// An occupancy grid map: the decoded image, its metadata and its classified cells.
#[derive(Debug, Clone, PartialEq)]
pub struct OccupancyMap {
    raster: Raster,
    yaml: MapYaml,
    classifier: Classifier,
    classified: Grid<Cell>,
}

impl OccupancyMap {
    /// Loads a PGM or PNG from memory with the default classifier and limits.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, MapError> {
        Self::from_image_bytes(bytes, Classifier::default(), &Limits::default())
    }

    /// Loads a PGM or PNG from memory with the given classifier and limits.
    pub fn from_image_bytes(bytes: &[u8], classifier: Classifier, limits: &Limits) -> Result<Self, MapError> {
        classifier.validate()?;
        let raster = decode_image(bytes, limits)?;
        Ok(Self::from_raster(raster, MapYaml::for_image("map.pgm"), classifier))
    }

    /// Loads a ROS map_server pair from the YAML text and the bytes of the image it names.
    pub fn from_yaml_and_image(yaml_text: &str, image: &[u8], limits: &Limits) -> Result<Self, MapError> {
        let yaml = MapYaml::parse(yaml_text)?;
        let classifier = Classifier::from_yaml(&yaml);
        classifier.validate()?;
        let raster = decode_image(image, limits)?;
        Ok(Self::from_raster(raster, yaml, classifier))
    }

    /// [`OccupancyMap::from_yaml_and_image`] for a PGM image only (e.g. what
    /// [`OccupancyMap::to_pgm`] and [`OccupancyMap::to_yaml`] write): for a caller that should
    /// not carry the PNG decoder, as the browser's plan module, which gets the map this way.
    ///
    /// ```
    /// use ksmcmc::grid::{Limits, OccupancyMap};
    /// let map = OccupancyMap::from_bytes(b"P2 3 1 255\n0 205 254\n").unwrap();
    /// let back = OccupancyMap::from_yaml_and_pgm(&map.to_yaml("map.pgm"), &map.to_pgm(), &Limits::default()).unwrap();
    /// assert_eq!(back.classified(), map.classified());
    /// assert!(OccupancyMap::from_yaml_and_pgm(&map.to_yaml("map.png"), b"\x89PNG\r\n\x1a\n", &Limits::default()).is_err());
    /// ```
    pub fn from_yaml_and_pgm(yaml_text: &str, pgm_bytes: &[u8], limits: &Limits) -> Result<Self, MapError> {
        let yaml = MapYaml::parse(yaml_text)?;
        let classifier = Classifier::from_yaml(&yaml);
        classifier.validate()?;
        let raster = pgm::decode(pgm_bytes, limits)?;
        Ok(Self::from_raster(raster, yaml, classifier))
    }

    /// Wraps an already decoded raster.
    pub fn from_raster(raster: Raster, yaml: MapYaml, classifier: Classifier) -> Self {
        let classified = classify(&raster, &classifier, yaml.resolution);
        OccupancyMap { raster, yaml, classifier, classified }
    }

    /// A map made directly from classes, e.g. one a person painted. Its raster is the
    /// conventional rendering (occupied 0, unknown 205, free 254 of 255), which map_server's
    /// trinary rule reads back to the same classes; the inside of solid occupied masses then
    /// becomes unknown, as for every map ([`hidden`]).
    pub fn from_classified(classified: Grid<Cell>) -> Self {
        let gray = classified.map(|c| gray_of(*c) as u16 * 257);
        let yaml = MapYaml::for_image("map.pgm");
        let classifier =
            Classifier::MapServer { negate: false, occupied_thresh: 0.65, free_thresh: 0.196, mode: Mode::Trinary };
        let classified = hidden::hide_interior(&classified, hidden::depth_cells(yaml.resolution));
        OccupancyMap { raster: Raster { gray, alpha: None }, yaml, classifier, classified }
    }

    /// The same map with other metadata (resolution, origin): for a map made from classes that
    /// stands for a real one, such as a snapshot of a map being explored. The cells are
    /// classified again, since how deep a solid mass is hidden depends on the resolution.
    pub fn with_yaml(mut self, yaml: MapYaml) -> Self {
        self.yaml = yaml;
        self.classified = classify(&self.raster, &self.classifier, self.yaml.resolution);
        self
    }

    /// Loads a map file: a `.yaml`/`.yml` map_server description (with the image it names,
    /// relative to the YAML's folder), or a PGM/PNG image.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn load(path: &std::path::Path, limits: &Limits) -> Result<Self, MapError> {
        let io = |p: &std::path::Path, e: std::io::Error| MapError::Io {
            path: p.display().to_string(),
            message: e.to_string(),
        };
        let bytes = std::fs::read(path).map_err(|e| io(path, e))?;
        let is_yaml = matches!(path.extension().and_then(|e| e.to_str()), Some("yaml" | "yml"));
        if !is_yaml {
            return Self::from_image_bytes(&bytes, Classifier::default(), limits);
        }
        let text = std::str::from_utf8(&bytes)
            .map_err(|e| MapError::NotUtf8 { what: path.display().to_string(), offset: e.valid_up_to() })?;
        let yaml = MapYaml::parse(text)?;
        let image_path = path.parent().unwrap_or(std::path::Path::new(".")).join(&yaml.image);
        let image = match std::fs::read(&image_path) {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                return Err(MapError::MissingImage {
                    path: image_path.display().to_string(),
                    yaml: path.display().to_string(),
                })
            }
            Err(e) => return Err(io(&image_path, e)),
        };
        Self::from_yaml_and_image(text, &image, limits)
    }

    /// Loads a map file exactly as `ksmcmc floorplan` reads it: [`OccupancyMap::load`] with
    /// the one classification rule for every format ([`Classifier::for_map`]), so that a PNG,
    /// a PGM and a `map.yaml` of the same pixels give the same cells.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn open(path: &std::path::Path, limits: &Limits) -> Result<Self, MapError> {
        let mut map = Self::load(path, limits)?;
        map.set_classifier(Classifier::for_map(map.yaml()))?;
        Ok(map)
    }

    /// A map from 8-bit pixels in memory, row-major from the top-left (as a PGM of the same
    /// pixels: 0 black, 255 white), described by `yaml` (its `image` is not read), classified
    /// by [`Classifier::for_map`]. Refused if `pixels` is not `width` x `height` or the map is
    /// over `limits`.
    ///
    /// ```
    /// use ksmcmc::grid::{Cell, Limits, MapYaml, OccupancyMap};
    /// let map = OccupancyMap::from_pixels(3, 1, &[0, 205, 254], MapYaml::for_image("m.pgm"), &Limits::default())?;
    /// assert_eq!(map.classified().cells(), &[Cell::Occupied, Cell::Unknown, Cell::Free]);
    /// assert!(OccupancyMap::from_pixels(2, 2, &[0; 3], MapYaml::for_image("m.pgm"), &Limits::default()).is_err());
    /// # Ok::<(), ksmcmc::grid::MapError>(())
    /// ```
    pub fn from_pixels(
        width: usize,
        height: usize,
        pixels: &[u8],
        yaml: MapYaml,
        limits: &Limits,
    ) -> Result<Self, MapError> {
        let (w, h) = limits.check(width as u64, height as u64)?;
        if pixels.len() != w * h {
            return Err(MapError::BadCells {
                message: format!("{} pixels for a {w}x{h} map: give one per cell, {} in all", pixels.len(), w * h),
            });
        }
        let gray = Grid::from_vec(w, h, pixels.iter().map(|&v| u16::from(v) * 257).collect())
            .expect("the size was checked above");
        let classifier = Classifier::for_map(&yaml);
        classifier.validate()?;
        Ok(Self::from_raster(Raster { gray, alpha: None }, yaml, classifier))
    }

    /// A map from occupancy values in the ROS `nav_msgs/OccupancyGrid` convention (-1 unknown,
    /// 0 - 100 the occupancy in percent), rows as an image's rows (from the top: a message's
    /// `data` starts at the bottom row, so turn it upside down first). Each value becomes the
    /// pixel `map_saver` writes for it under `yaml`'s thresholds (occupied 0 above
    /// `occupied_thresh`, free 254 below `free_thresh`, unknown 205 otherwise), and the pixels
    /// are read as [`OccupancyMap::from_pixels`] reads them: so a grid and the image
    /// `map_saver` saves of it give the same map. Values outside -1..=100 are refused.
    ///
    /// ```
    /// use ksmcmc::grid::{Cell, Limits, MapYaml, OccupancyMap};
    /// let yaml = MapYaml::for_image("m.pgm");
    /// let grid = OccupancyMap::from_occupancy(3, 1, &[100, -1, 0], yaml.clone(), &Limits::default())?;
    /// assert_eq!(grid.classified().cells(), &[Cell::Occupied, Cell::Unknown, Cell::Free]);
    /// let image = OccupancyMap::from_pixels(3, 1, &[0, 205, 254], yaml.clone(), &Limits::default())?;
    /// assert_eq!(grid.classified(), image.classified());
    /// assert!(OccupancyMap::from_occupancy(1, 1, &[101], yaml, &Limits::default()).is_err());
    /// # Ok::<(), ksmcmc::grid::MapError>(())
    /// ```
    pub fn from_occupancy(
        width: usize,
        height: usize,
        values: &[i8],
        yaml: MapYaml,
        limits: &Limits,
    ) -> Result<Self, MapError> {
        if let Some(i) = values.iter().position(|&v| !(-1..=100).contains(&v)) {
            return Err(MapError::BadCells {
                message: format!(
                    "occupancy value {} at index {i}: an OccupancyGrid holds -1 (unknown) or 0 - 100 (percent)",
                    values[i]
                ),
            });
        }
        let pixel = |v: i8| match v {
            -1 => 205,
            v if f64::from(v) / 100.0 > yaml.occupied_thresh => 0,
            v if f64::from(v) / 100.0 < yaml.free_thresh => 254,
            _ => 205,
        };
        let pixels: Vec<u8> = values.iter().map(|&v| pixel(v)).collect();
        Self::from_pixels(width, height, &pixels, yaml, limits)
    }

    /// Reclassifies every cell with another rule.
    pub fn set_classifier(&mut self, classifier: Classifier) -> Result<(), MapError> {
        classifier.validate()?;
        self.classifier = classifier;
        self.classified = classify(&self.raster, &classifier, self.yaml.resolution);
        Ok(())
    }

    /// Map width in cells.
    pub fn width(&self) -> usize {
        self.classified.width()
    }

    /// Map height in cells.
    pub fn height(&self) -> usize {
        self.classified.height()
    }

    /// The classified cells `C_M` of eq. 3.7, with the inside of solid occupied masses, which no
    /// sensor saw, unknown ([`hidden`]).
    pub fn classified(&self) -> &Grid<Cell> {
        &self.classified
    }

    /// The decoded image.
    pub fn raster(&self) -> &Raster {
        &self.raster
    }

    /// Resolution, origin and thresholds (defaults for plain images).
    pub fn yaml(&self) -> &MapYaml {
        &self.yaml
    }

    /// The rule in force.
    pub fn classifier(&self) -> &Classifier {
        &self.classifier
    }

    /// How many cells have class `c`.
    pub fn count(&self, c: Cell) -> usize {
        self.classified.cells().iter().filter(|&&x| x == c).count()
    }

    /// The classified map as an 8-bit binary PGM in the ROS convention (occupied 0, unknown 205,
    /// free 254), which map_server reads back to the same classes with the YAML of
    /// [`OccupancyMap::to_yaml`].
    pub fn to_pgm(&self) -> Vec<u8> {
        let samples: Vec<u8> = self.classified.cells().iter().map(|&c| gray_of(c)).collect();
        pgm::encode_u8(self.width(), self.height(), &samples)
    }

    /// The `map.yaml` for [`OccupancyMap::to_pgm`] saved as `image_name`.
    pub fn to_yaml(&self, image_name: &str) -> String {
        MapYaml {
            image: image_name.to_string(),
            negate: false,
            occupied_thresh: 0.65,
            free_thresh: 0.196,
            mode: Mode::Trinary,
            ..self.yaml.clone()
        }
        .to_text()
    }
}

/// The ROS gray level of a class: occupied 0, unknown 205, free 254.
pub fn gray_of(c: Cell) -> u8 {
    match c {
        Cell::Occupied => 0,
        Cell::Unknown => 205,
        Cell::Free => 254,
    }
}
