//! Maps and their pictures in the browser: the JavaScript class `Map` (a classified occupancy
//! map, read from PGM, PNG, a ROS `map.yaml` pair or cell codes) and `renderRgba` /
//! `drawToCanvas`, the native renderer's pixels. In the mapper module (`ksmcmc.js`); the other
//! modules take a map as bytes (its `toPgm()` and `toYaml()`), since a `Map` lives in this
//! module's memory.

use super::put_rgba;
use crate::floorplan::World;
use crate::grid::{Cell, Classifier, Grid, Limits, OccupancyMap};
use crate::render::{self, RenderOptions};
use serde::{Deserialize, Serialize};
use wasm_bindgen::prelude::*;
use wasm_bindgen::Clamped;

/// The number of cells of each class in a map, as `map.counts()` returns it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Counts {
    /// Free cells (code 0).
    pub free: u32,
    /// Unknown cells (code 1).
    pub unknown: u32,
    /// Occupied cells (code 2).
    pub occupied: u32,
}

/// A classified occupancy map.
///
/// Cell codes (eq. 3.7): 0 free, 1 unknown, 2 occupied; cells are row-major from the top-left.
#[wasm_bindgen]
#[derive(Debug, Clone)]
pub struct Map {
    inner: OccupancyMap,
}

impl Map {
    /// Wraps a library map.
    pub fn new(inner: OccupancyMap) -> Map {
        Map { inner }
    }

    /// The library map.
    pub fn inner(&self) -> &OccupancyMap {
        &self.inner
    }
}

#[wasm_bindgen]
impl Map {
    /// Loads a map image: a PGM (P2 or P5, 8 or 16 bits) or a PNG of any colour type, told
    /// apart by their first bytes. Cells are classified with the default intensity rule.
    /// Throws an `Error` that says what is wrong with the data.
    #[wasm_bindgen(js_name = fromBytes)]
    pub fn from_bytes(bytes: &[u8]) -> Result<Map, JsError> {
        Ok(Map::new(OccupancyMap::from_bytes(bytes)?))
    }

    /// Loads a ROS map_server pair: the text of `map.yaml` and the bytes of the image it
    /// names (the caller matches the `image:` name to a file). Cells are classified with the
    /// YAML's own rule and thresholds.
    #[wasm_bindgen(js_name = fromYaml)]
    pub fn from_yaml(
        #[wasm_bindgen(js_name = yamlText)] yaml_text: &str,
        #[wasm_bindgen(js_name = imageBytes)] image_bytes: &[u8],
    ) -> Result<Map, JsError> {
        Ok(Map::new(OccupancyMap::from_yaml_and_image(yaml_text, image_bytes, &Limits::default())?))
    }

    /// A map from cell codes, e.g. one a person painted: `codes` holds `width * height` bytes,
    /// each 0 (free), 1 (unknown) or 2 (occupied), row-major from the top-left.
    #[wasm_bindgen(js_name = fromCells)]
    pub fn from_cells(width: u32, height: u32, codes: &[u8]) -> Result<Map, JsError> {
        let (w, h) = Limits::default().check(width.into(), height.into())?;
        if codes.len() != w * h {
            return Err(JsError::new(&format!(
                "a {w}x{h} map needs {} cell codes, but {} were given",
                w * h,
                codes.len()
            )));
        }
        let mut cells = Vec::with_capacity(codes.len());
        for (i, &code) in codes.iter().enumerate() {
            let cell = Cell::from_code(code).ok_or_else(|| {
                JsError::new(&format!(
                    "cell code {code} at ({}, {}) is not 0 (free), 1 (unknown) or 2 (occupied)",
                    i % w,
                    i / w
                ))
            })?;
            cells.push(cell);
        }
        let grid = Grid::from_vec(w, h, cells).ok_or_else(|| JsError::new("cell count mismatch"))?;
        Ok(Map::new(OccupancyMap::from_classified(grid)))
    }

    /// Width in cells.
    #[wasm_bindgen(getter)]
    pub fn width(&self) -> u32 {
        self.inner.width() as u32
    }

    /// Height in cells.
    #[wasm_bindgen(getter)]
    pub fn height(&self) -> u32 {
        self.inner.height() as u32
    }

    /// How many cells are free, unknown and occupied.
    #[wasm_bindgen(unchecked_return_type = "{ free: number; unknown: number; occupied: number }")]
    pub fn counts(&self) -> Result<JsValue, JsError> {
        Ok(serde_wasm_bindgen::to_value(&self.counts_struct())?)
    }

    /// The cell codes, `width * height` bytes row-major: 0 free, 1 unknown, 2 occupied. A
    /// copy: change it and build a new map with `Map.fromCells`.
    pub fn cells(&self) -> Vec<u8> {
        self.inner.classified().cells().iter().map(|c| c.code()).collect()
    }

    /// The classified map as an 8-bit binary PGM in the ROS convention (occupied 0, unknown
    /// 205, free 254).
    #[wasm_bindgen(js_name = toPgm)]
    pub fn to_pgm(&self) -> Vec<u8> {
        self.inner.to_pgm()
    }

    /// The same image classified by another rule, as a new map: `'auto'` finds the background
    /// grays from the histogram and counts anti-aliased wall edges as occupied (what
    /// `ksmcmc floorplan --classify auto`, its default, does to every map, so that a PNG, a PGM
    /// and a map.yaml of the same pixels give the same cells; a YAML with `negate: 1` or
    /// `mode: raw` keeps its own rule), `'fixed'` applies the default intensity thresholds
    /// (what `Map.fromBytes` does; a map read with `Map.fromYaml` has its YAML's rule until
    /// reclassified).
    pub fn reclassify(
        &self,
        #[wasm_bindgen(unchecked_param_type = "'auto' | 'fixed'")] rule: &str,
    ) -> Result<Map, JsError> {
        let classifier = match rule {
            "auto" => Classifier::for_map(self.inner.yaml()),
            "fixed" => Classifier::default(),
            other => return Err(JsError::new(&format!("classify: {other:?} is neither 'auto' nor 'fixed'"))),
        };
        let mut inner = self.inner.clone();
        inner.set_classifier(classifier)?;
        Ok(Map::new(inner))
    }

    /// The `map.yaml` text for `toPgm()` saved under the file name `imageName`.
    #[wasm_bindgen(js_name = toYaml)]
    pub fn to_yaml(&self, #[wasm_bindgen(js_name = imageName)] image_name: &str) -> String {
        self.inner.to_yaml(image_name)
    }
}

impl Map {
    /// The class counts as a Rust struct.
    pub fn counts_struct(&self) -> Counts {
        let n = |c| self.inner.count(c) as u32;
        Counts { free: n(Cell::Free), unknown: n(Cell::Unknown), occupied: n(Cell::Occupied) }
    }
}

/// Rendered pixels: `width * height` straight (not premultiplied) RGBA pixels, row-major.
#[wasm_bindgen]
#[derive(Debug, Clone)]
pub struct Rendered {
    width: u32,
    height: u32,
    rgba: Vec<u8>,
}

#[wasm_bindgen]
impl Rendered {
    /// Width in pixels.
    #[wasm_bindgen(getter)]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    #[wasm_bindgen(getter)]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The pixels, `4 * width * height` bytes, ready for `new ImageData(rgba, width)`. Each
    /// read makes a fresh copy.
    #[wasm_bindgen(getter)]
    pub fn rgba(&self) -> Clamped<Vec<u8>> {
        Clamped(self.rgba.clone())
    }
}

impl Rendered {
    /// Wraps straight RGBA pixels.
    pub fn new(width: u32, height: u32, rgba: Vec<u8>) -> Rendered {
        Rendered { width, height, rgba }
    }

    /// The pixels without a copy.
    pub fn rgba_bytes(&self) -> &[u8] {
        &self.rgba
    }
}

/// Renders a map, with the world of a `world.json` text over it if given, exactly as the
/// native renderer does. `scale` is output pixels per map cell (default 1); `labels` draws
/// each unit's type and id (default true).
#[wasm_bindgen(js_name = renderRgba)]
pub fn render_rgba(
    map: &Map,
    #[wasm_bindgen(js_name = worldJson)] world_json: Option<String>,
    scale: Option<u32>,
    labels: Option<bool>,
) -> Result<Rendered, JsError> {
    let options = options(map, scale, labels)?;
    let world = world_json.as_deref().map(World::from_json).transpose()?;
    let pixmap = render::render(map.inner.classified(), world.as_ref(), &options);
    Ok(Rendered { width: pixmap.width(), height: pixmap.height(), rgba: render::to_rgba(&pixmap) })
}

/// Renders like `renderRgba` and puts the pixels on `canvas` with `ImageData`, resizing the
/// canvas to the rendered size. Scale it for display with CSS (`image-rendering: pixelated`).
#[wasm_bindgen(js_name = drawToCanvas)]
pub fn draw_to_canvas(
    canvas: &web_sys::HtmlCanvasElement,
    map: &Map,
    #[wasm_bindgen(js_name = worldJson)] world_json: Option<String>,
    scale: Option<u32>,
    labels: Option<bool>,
) -> Result<(), JsError> {
    let rendered = render_rgba(map, world_json, scale, labels)?;
    put_rgba(canvas, rendered.width, rendered.height, rendered.rgba_bytes())
}

/// Checks scale and output size ([`render::check_size`]) before anything is allocated.
// `..defaults` keeps this compiling when the renderer grows options.
#[allow(clippy::needless_update)]
fn options(map: &Map, scale: Option<u32>, labels: Option<bool>) -> Result<RenderOptions, JsError> {
    let defaults = RenderOptions::default();
    let scale = scale.unwrap_or(defaults.scale);
    render::check_size(map.inner.width(), map.inner.height(), scale)?;
    Ok(RenderOptions { scale, labels: labels.unwrap_or(defaults.labels), ..defaults })
}

/// Every row of the legend the renderer can draw, as JSON: `[{ "name": "room", "rgba":
/// [r, g, b, a] }, …]` (straight RGBA over white), in the order drawn. A page that draws its
/// legend beside the map (drawn with `legend: false`) lists these, so that its colours are
/// the picture's.
#[wasm_bindgen(js_name = legendJson)]
pub fn legend_json() -> String {
    // Written by hand: the names are plain words, and the mapper module has no room for a JSON
    // value type (tests/e2e/size.test.mjs).
    let rows: Vec<String> = render::legend_palette()
        .into_iter()
        .map(|(name, [r, g, b, a])| format!("{{\"name\":\"{name}\",\"rgba\":[{r},{g},{b},{a}]}}"))
        .collect();
    format!("[{}]", rows.join(","))
}
