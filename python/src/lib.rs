//! `ksmcmc._ksmcmc`: the Python package's native part.
//!
//! Thin, as the WebAssembly and command-line bindings are: it turns Python's arguments into the
//! crate's types, runs what `ksmcmc floorplan` runs ([`ksmcmc::floorplan::run::run`], with the
//! GIL released), and turns the results into bytes and text for `ksmcmc/__init__.py`, which
//! makes numpy arrays and dicts of them. Every failure of the core comes back as a Python
//! exception with the core's message: `OSError` for files, `ValueError` for everything else;
//! nothing panics across the boundary.

use ksmcmc::floorplan::edits::Edits;
use ksmcmc::floorplan::georef::Georef;
use ksmcmc::floorplan::knowledge::IndoorKnowledge;
use ksmcmc::floorplan::route::RoutePlanner;
use ksmcmc::floorplan::run::{run, Run, RunOptions};
use ksmcmc::floorplan::ChainConfig;
use ksmcmc::grid::{Limits, MapError, MapYaml, OccupancyMap};
use ksmcmc::mln::{learn_weights, Database, GroundConfig, InferenceConfig, LearnConfig, Mln, Network};
use ksmcmc::render::Outputs;
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::path::PathBuf;
use std::sync::OnceLock;

/// A map error as Python's exception: `OSError` where a file could not be read.
fn map_error(e: MapError) -> PyErr {
    match e {
        MapError::Io { .. } | MapError::MissingImage { .. } => PyOSError::new_err(e.to_string()),
        e => PyValueError::new_err(e.to_string()),
    }
}

/// Any other failure of the core as `ValueError`, with its message.
fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// A floor plan: the map, and what the run found on it.
#[pyclass(module = "ksmcmc._ksmcmc", frozen)]
struct FloorPlan {
    map: OccupancyMap,
    run: Run,
    /// The nine files, made when first asked for.
    outputs: OnceLock<Outputs>,
}

impl FloorPlan {
    fn outputs(&self) -> PyResult<&Outputs> {
        if let Some(o) = self.outputs.get() {
            return Ok(o);
        }
        let o = self.outputs_with(None)?;
        Ok(self.outputs.get_or_init(|| o))
    }

    fn outputs_with(&self, georef: Option<&Georef>) -> PyResult<Outputs> {
        let r = &self.run;
        Outputs::new(&self.map, &r.world, &r.labels, &r.report, r.trace.clone(), georef, &Default::default())
            .map_err(value_error)
    }
}

#[pymethods]
impl FloorPlan {
    /// The room labels as little-endian `u16` bytes, row-major, with the width and height.
    fn labels_le<'py>(&self, py: Python<'py>) -> (Bound<'py, PyBytes>, usize, usize) {
        let l = &self.run.labels;
        let bytes: Vec<u8> = l.cells().iter().flat_map(|v| v.to_le_bytes()).collect();
        (PyBytes::new(py, &bytes), l.width(), l.height())
    }

    /// `world.json`.
    fn world_json(&self) -> String {
        self.run.world.to_json()
    }

    /// `report.json`.
    fn report_json(&self) -> PyResult<String> {
        Ok(self.outputs()?.report_json.clone())
    }

    /// `graph.json`.
    fn graph_json(&self) -> PyResult<String> {
        Ok(self.outputs()?.graph_json.clone())
    }

    /// `world.geojson`, placed on the Earth by `georef` (`"LAT,LON,BEARING"`) when given.
    #[pyo3(signature = (georef=None))]
    fn geojson(&self, georef: Option<&str>) -> PyResult<String> {
        match georef {
            None => Ok(self.outputs()?.world_geojson.clone()),
            Some(text) => {
                let g: Georef = text.parse().map_err(|e| value_error(format!("georef {text:?}: {e}")))?;
                Ok(self.outputs_with(Some(&g))?.world_geojson)
            }
        }
    }

    /// `world.svg`.
    fn svg(&self) -> PyResult<String> {
        Ok(self.outputs()?.world_svg.clone())
    }

    /// `world.glb`.
    fn glb<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        Ok(PyBytes::new(py, &self.outputs()?.world_glb))
    }

    /// `overlay.png`.
    fn png<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        Ok(PyBytes::new(py, &self.outputs()?.overlay_png))
    }

    /// The files `ksmcmc floorplan` writes, by name.
    fn files<'py>(&self, py: Python<'py>) -> PyResult<Vec<(&'static str, Bound<'py, PyBytes>)>> {
        Ok(self.outputs()?.files().iter().map(|(name, bytes)| (*name, PyBytes::new(py, bytes))).collect())
    }

    /// A route from map cell `start` to `goal` (column, row) through the rooms and doors, as
    /// JSON (`ksmcmc route`'s output).
    fn route(&self, py: Python<'_>, start: (i64, i64), goal: (i64, i64)) -> PyResult<String> {
        let r = &self.run;
        let (map, labels) = (self.map.classified().clone(), r.labels.clone());
        let resolution = self.map.yaml().resolution;
        py.detach(|| {
            let mut planner = RoutePlanner::new(map, labels, &r.world, resolution)?;
            planner.route(start, goal).map(|route| route.to_json())
        })
        .map_err(value_error)
    }
}

/// The chain's settings for `knowledge`: `builtin`, `none`, `handset`, or the path of an
/// indoor knowledge base (`.mln`), as `ksmcmc floorplan --knowledge` takes it.
fn chain_config(knowledge: &str) -> PyResult<ChainConfig> {
    let mut config = ChainConfig::default();
    IndoorKnowledge::named(knowledge, |path| std::fs::read_to_string(path))
        .map_err(|e| if e.is_unreadable() { PyOSError::new_err(e.to_string()) } else { value_error(e.to_string()) })?
        .apply_to(&mut config.knowledge);
    Ok(config)
}

/// Runs the floor plan of `map` as `ksmcmc floorplan` does, without the GIL.
fn explain(
    py: Python<'_>,
    map: OccupancyMap,
    name: String,
    seed: u64,
    iterations: u64,
    knowledge: &str,
    edits: Option<&str>,
) -> PyResult<FloorPlan> {
    let config = chain_config(knowledge)?;
    let edits = edits.map(Edits::parse).transpose().map_err(|e| value_error(format!("edits: {e}")))?;
    let options = RunOptions { seed, iterations, config, edits, wings: true };
    let mut result = py.detach(|| run(&map, &options)).map_err(value_error)?;
    // The report as the command line writes it for the same map.
    result.report["map"] = name.into();
    result.report["cell_prediction_rate_region"] = serde_json::Value::Null;
    Ok(FloorPlan { map, run: result, outputs: OnceLock::new() })
}

/// Checks a resolution given by the caller: metres per cell, above 0 and at most 10.
fn check_resolution(r: f64) -> PyResult<f64> {
    if r.is_finite() && r > 0.0 && r <= 10.0 {
        Ok(r)
    } else {
        Err(value_error(format!("resolution must be the metres per cell, above 0 and at most 10, not {r}")))
    }
}

/// The floor plan of a map file (PNG, PGM or `map.yaml`), read as `ksmcmc floorplan` reads it.
#[pyfunction]
#[pyo3(signature = (path, resolution, seed, iterations, knowledge, edits))]
fn floorplan_path(
    py: Python<'_>,
    path: PathBuf,
    resolution: Option<f64>,
    seed: u64,
    iterations: u64,
    knowledge: &str,
    edits: Option<&str>,
) -> PyResult<FloorPlan> {
    let mut map = OccupancyMap::open(&path, &Limits::default()).map_err(map_error)?;
    if let Some(r) = resolution {
        let yaml = MapYaml { resolution: check_resolution(r)?, ..map.yaml().clone() };
        map = map.with_yaml(yaml);
    }
    explain(py, map, path.display().to_string(), seed, iterations, knowledge, edits)
}

/// The floor plan of cells in memory: `kind` `"pixels"` (8-bit map image pixels) or
/// `"occupancy"` (`nav_msgs/OccupancyGrid` values as bytes of `int8`), row-major from the top.
#[pyfunction]
#[pyo3(signature = (width, height, cells, kind, resolution, origin, seed, iterations, knowledge, edits))]
#[allow(clippy::too_many_arguments)]
fn floorplan_cells(
    py: Python<'_>,
    width: usize,
    height: usize,
    cells: &[u8],
    kind: &str,
    resolution: f64,
    origin: (f64, f64, f64),
    seed: u64,
    iterations: u64,
    knowledge: &str,
    edits: Option<&str>,
) -> PyResult<FloorPlan> {
    let yaml = MapYaml {
        resolution: check_resolution(resolution)?,
        origin: [origin.0, origin.1, origin.2],
        ..MapYaml::for_image("map.pgm")
    };
    let limits = Limits::default();
    let map = match kind {
        "pixels" => OccupancyMap::from_pixels(width, height, cells, yaml, &limits),
        "occupancy" => {
            let values: Vec<i8> = cells.iter().map(|&b| b as i8).collect();
            OccupancyMap::from_occupancy(width, height, &values, yaml, &limits)
        }
        other => return Err(value_error(format!("cells must be \"pixels\" or \"occupancy\", not {other:?}"))),
    }
    .map_err(map_error)?;
    explain(py, map, "array".to_string(), seed, iterations, knowledge, edits)
}

/// Marginal probabilities of the ground atoms of the `queries` predicates, as `ksmcmc mln
/// query` prints them: (atom, probability) in its order.
#[pyfunction]
#[pyo3(signature = (kb, evidence, queries))]
fn mln_query(py: Python<'_>, kb: &str, evidence: &str, queries: Vec<String>) -> PyResult<Vec<(String, f64)>> {
    let mln = Mln::parse(kb).map_err(|e| value_error(format!("the rules: {e}")))?;
    let db = Database::parse(evidence, &mln).map_err(|e| value_error(format!("the evidence: {e}")))?;
    let names: Vec<&str> = queries.iter().map(String::as_str).collect();
    py.detach(|| {
        let net = Network::ground(&mln, &db, &GroundConfig::query(&names))?;
        let m = net.infer_marginals(&InferenceConfig::default())?;
        Ok(m.iter().map(|(atom, p)| (atom.to_string(), p)).collect())
    })
    .map_err(|e: ksmcmc::mln::MlnError| value_error(format!("inference: {e}")))
}

/// The rules `kb` with weights learned from the training `databases` (`ksmcmc mln learn`),
/// as the text of an `.mln` file.
#[pyfunction]
#[pyo3(signature = (kb, databases, queries))]
fn mln_learn(py: Python<'_>, kb: &str, databases: Vec<String>, queries: Vec<String>) -> PyResult<String> {
    let mln = Mln::parse(kb).map_err(|e| value_error(format!("the rules: {e}")))?;
    let mut dbs = Vec::new();
    for (i, text) in databases.iter().enumerate() {
        dbs.push(Database::parse(text, &mln).map_err(|e| value_error(format!("database {i}: {e}")))?);
    }
    let config = LearnConfig { query: queries, ..LearnConfig::default() };
    let learned =
        py.detach(|| learn_weights(&mln, &dbs, &config)).map_err(|e| value_error(format!("learning: {e}")))?;
    Ok(learned.to_mln(&mln, "Weights learned by ksmcmc.mln.learn (pseudo-log-likelihood by default)."))
}

/// The module.
#[pymodule]
fn _ksmcmc(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<FloorPlan>()?;
    m.add_function(wrap_pyfunction!(floorplan_path, m)?)?;
    m.add_function(wrap_pyfunction!(floorplan_cells, m)?)?;
    m.add_function(wrap_pyfunction!(mln_query, m)?)?;
    m.add_function(wrap_pyfunction!(mln_learn, m)?)?;
    Ok(())
}
