//! Synthetic table-top scenes with ground truth (`ksmcmc tabletop-synth`).
//!
//! A scene is built from *groups* of boxes placed apart on the table, each a configuration the
//! dissertation's figures show:
//!
//! * **resting**: a box standing on the table;
//! * **stack**: a box on a box (sometimes three high);
//! * **leaning**: a plank leaning against a box, one edge on the table and one face on the
//!   box's top edge (unstable, in contact with both, like #4 of Fig. 4.9-b);
//! * **hovering**: a box resting on a smaller box that the camera does not report (it is
//!   listed under `hidden_objects`), so the visible box seems to hover: its truth is
//!   `hidden: true`.
//!
//! Then **false estimates** are added: tilted boxes (at least 20 degrees from any stable pose)
//! that cut 2 to 4 cm deep into a stable object, as a spurious pose hypothesis would, and touch
//! nothing else. Their truth is `false: true`.
//!
//! Every visible box gets keypoints: points on its faces that face the camera, projected
//! through the camera (into both images of the stereo pair, by default 12 cm apart) at its
//! true pose (for a false estimate, the spurious pose its matches
//! imply) with Gaussian pixel noise. Its estimated pose is the true pose with Gaussian noise.
//! Occlusion is not modelled.
//!
//! The generator draws only from [`crate::mcmc::Rng`] and uses libm, so a seed gives the same
//! scene, byte for byte, natively and in WebAssembly.
//!
//! ```
//! use ksmcmc::tabletop::synth::{generate, SynthConfig};
//!
//! let config = SynthConfig { hovering: Some(1), false_estimates: Some(1), ..Default::default() };
//! let scene = generate(&config, 42).unwrap();
//! let truth = |f: fn(&ksmcmc::tabletop::scene::Truth) -> bool| {
//!     scene.objects.iter().filter(|o| f(o.truth.as_ref().unwrap())).count()
//! };
//! assert_eq!(truth(|t| t.hidden), 1);
//! assert_eq!(truth(|t| t.false_estimate), 1);
//! assert_eq!(scene.hidden_objects.len(), 1);
//! assert_eq!(generate(&config, 42).unwrap(), scene); // deterministic
//! ```

use super::chain::perturb;
use super::geometry::{penetration, relation, Obb, Relation, Tolerances};
use super::scene::{Camera, HiddenObject, Keypoint, Pose, Scene, SceneObject, Table, Truth};
use crate::mcmc::Rng;
use crate::setting::{check, require, InvalidSetting};
use nalgebra::{Isometry3, Matrix3, Quaternion, Rotation3, Translation3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// What to generate. Every field has a default; JSON with any subset of fields deserialises
/// onto the defaults.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SynthConfig {
    /// Fewest visible objects (default 3).
    pub min_objects: u32,
    /// Most visible objects, false estimates included (default 10).
    pub max_objects: u32,
    /// Table top size, metres (default 1.0 x 0.7).
    pub table: [f64; 2],
    /// The part of the table objects are placed on, centred (default 0.7 x 0.5).
    pub area: [f64; 2],
    /// Image size, pixels (default 1280 x 960).
    pub image: [u32; 2],
    /// Focal length, pixels (default 1000).
    pub focal: f64,
    /// Camera distance from the table centre, metres: a range (default 0.75 - 0.95).
    pub distance: [f64; 2],
    /// Camera elevation above the table plane, degrees: a range (default 45 - 60).
    pub elevation_deg: [f64; 2],
    /// Camera azimuth from the table's `-y` side, degrees: a range (default -20 - 20).
    pub azimuth_deg: [f64; 2],
    /// Stereo baseline, metres; `None` for a single camera (default 0.12).
    pub baseline: Option<f64>,
    /// Keypoints per visible object (default 40).
    pub keypoints: u32,
    /// Standard deviation of keypoint pixel noise (default 1).
    pub pixel_noise: f64,
    /// Standard deviation of the estimated position per axis, metres (default 0.002).
    pub pose_noise_t: f64,
    /// Standard deviation of the estimated rotation per axis, radians (default 0.01).
    pub pose_noise_r: f64,
    /// Relative frequency of resting boxes, stacks, leaning planks and hovering boxes
    /// (default 4, 2.5, 1.5, 1).
    pub group_weights: [f64; 4],
    /// Exactly this many hovering boxes (hidden supports), instead of drawing them by weight.
    pub hovering: Option<u32>,
    /// Probability of each of up to two false estimates (default 0.3).
    pub false_probability: f64,
    /// Exactly this many false estimates, instead of drawing them.
    pub false_estimates: Option<u32>,
    /// Write the true poses into each object's `truth` (default true).
    pub record_poses: bool,
}

impl Default for SynthConfig {
    fn default() -> Self {
        SynthConfig {
            min_objects: 3,
            max_objects: 10,
            table: [1.0, 0.7],
            area: [0.7, 0.5],
            image: [1280, 960],
            focal: 1000.0,
            distance: [0.75, 0.95],
            elevation_deg: [45.0, 60.0],
            azimuth_deg: [-20.0, 20.0],
            baseline: Some(0.12),
            keypoints: 40,
            pixel_noise: 1.0,
            pose_noise_t: 0.002,
            pose_noise_r: 0.01,
            group_weights: [4.0, 2.5, 1.5, 1.0],
            hovering: None,
            false_probability: 0.3,
            false_estimates: None,
            record_poses: true,
        }
    }
}

impl SynthConfig {
    /// Parses a JSON config (missing fields take their defaults; blank text is the defaults)
    /// and validates it: what `ksmcmc tabletop-synth --config` and the wasm `tabletopSynth`
    /// read.
    ///
    /// ```
    /// use ksmcmc::tabletop::synth::SynthConfig;
    /// assert_eq!(SynthConfig::from_json(r#"{"max_objects": 5}"#).unwrap().max_objects, 5);
    /// let e = SynthConfig::from_json(r#"{"max_objects": 0}"#).unwrap_err().to_string();
    /// assert!(e.starts_with("invalid synthetic scene configuration: max_objects 0 must be"), "{e}");
    /// ```
    pub fn from_json(text: &str) -> Result<SynthConfig, SynthError> {
        let c = SynthConfig::parse_json(text)?;
        c.validate().map_err(SynthError::Setting)?;
        Ok(c)
    }

    /// Parses a JSON config like [`SynthConfig::from_json`] but leaves validation to the
    /// caller, who may change fields first (as the command line's options do).
    pub fn parse_json(text: &str) -> Result<SynthConfig, SynthError> {
        crate::json::settings(text, r#"{"max_objects": 5}"#).map_err(SynthError::Config)
    }

    /// Checks every field, naming the one at fault.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        let range =
            |r: [f64; 2], lo: f64, hi: f64| r.iter().all(|v| v.is_finite()) && lo <= r[0] && r[0] <= r[1] && r[1] <= hi;
        let (n, m) = (self.max_objects, self.min_objects);
        check((1..=40).contains(&n), "max_objects", n as f64, "from 1 to 40")?;
        check(m <= n, "min_objects", m as f64, "at most max_objects")?;
        let table = [self.table[0].min(self.table[1]), self.table[0].max(self.table[1])];
        require(range(table, 0.3, 10.0), "table", "metres from 0.3 to 10 each way")?;
        let area =
            self.area[0] <= self.table[0] && self.area[1] <= self.table[1] && self.area.iter().all(|&a| a >= 0.2);
        require(area, "area", "at least 0.2 m each way and fit on the table")?;
        let image = self.image.iter().all(|&p| (16..=20_000).contains(&p));
        require(image, "image", "from 16 to 20000 pixels each way")?;
        check(self.focal.is_finite() && self.focal > 0.0, "focal", self.focal, "a positive number")?;
        require(range(self.distance, 0.2, 20.0), "distance", "a range [a, b] with 0.2 <= a <= b <= 20")?;
        if let Some(b) = self.baseline {
            check(b.is_finite() && b > 0.0 && b <= 2.0, "baseline", b, "metres above 0, at most 2")?;
        }
        require(range(self.elevation_deg, 10.0, 90.0), "elevation_deg", "a range [a, b] with 10 <= a <= b <= 90")?;
        let azimuth = range(self.azimuth_deg, -180.0, 180.0);
        require(azimuth, "azimuth_deg", "a range [a, b] with -180 <= a <= b <= 180")?;
        check(self.keypoints <= 10_000, "keypoints", self.keypoints as f64, "at most 10000")?;
        let noises = [
            ("pixel_noise", self.pixel_noise),
            ("pose_noise_t", self.pose_noise_t),
            ("pose_noise_r", self.pose_noise_r),
        ];
        for (name, v) in noises {
            check(v.is_finite() && v >= 0.0, name, v, "a non-negative number")?;
        }
        let w = &self.group_weights;
        let weights = w.iter().all(|w| w.is_finite() && *w >= 0.0) && w.iter().sum::<f64>() > 0.0;
        require(weights, "group_weights", "non-negative with a positive sum")?;
        let p = self.false_probability;
        check((0.0..=1.0).contains(&p), "false_probability", p, "in [0, 1]")?;
        let falses = self.false_estimates.unwrap_or(0);
        let forced = self.hovering.unwrap_or(0) + falses + (falses > 0) as u32;
        // The false estimates need one object more to cut into.
        check(forced <= n, "hovering + false_estimates + 1", forced as f64, "at most max_objects")
    }
}

/// The role of a generated box.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Resting,
    Stacked,
    Leaning,
    Hovering,
    False,
}

impl Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::Resting => "resting",
            Kind::Stacked => "stacked",
            Kind::Leaning => "leaning",
            Kind::Hovering => "hovering",
            Kind::False => "false",
        }
    }
}

#[derive(Debug, Clone)]
struct Item {
    size: Vector3<f64>,
    pose: Isometry3<f64>,
    kind: Kind,
    visible: bool,
}

impl Item {
    fn obb(&self) -> Obb {
        Obb::new(self.pose.translation.vector, self.pose.rotation, self.size)
    }
}

fn uniform(rng: &mut Rng, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * rng.uniform()
}

fn yaw(angle: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::new_normalize(Quaternion::new(libm::cos(angle / 2.0), 0.0, 0.0, libm::sin(angle / 2.0)))
}

fn about_y(angle: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::new_normalize(Quaternion::new(libm::cos(angle / 2.0), 0.0, libm::sin(angle / 2.0), 0.0))
}

fn at(t: Vector3<f64>, q: UnitQuaternion<f64>) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::from(t), q)
}

/// A box standing upright on the table, centred at the group origin.
fn upright(size: Vector3<f64>, base_z: f64, kind: Kind) -> Item {
    Item { size, pose: at(Vector3::new(0.0, 0.0, base_z + size.z / 2.0), yaw(0.0)), kind, visible: true }
}

fn group_resting(rng: &mut Rng) -> Vec<Item> {
    let size = Vector3::new(uniform(rng, 0.05, 0.16), uniform(rng, 0.05, 0.16), uniform(rng, 0.04, 0.22));
    vec![upright(size, 0.0, Kind::Resting)]
}

fn group_stack(rng: &mut Rng, budget: u32) -> Vec<Item> {
    let base = Vector3::new(uniform(rng, 0.09, 0.18), uniform(rng, 0.09, 0.18), uniform(rng, 0.04, 0.12));
    let mut items = vec![upright(base, 0.0, Kind::Resting)];
    let levels = if budget >= 3 && rng.uniform() < 0.3 { 2 } else { 1 };
    for _ in 0..levels {
        let below = items.last().expect("the base").clone();
        let (bw, bd) = (below.size.x, below.size.y);
        let size =
            Vector3::new(uniform(rng, 0.04, bw.max(0.05)), uniform(rng, 0.04, bd.max(0.05)), uniform(rng, 0.03, 0.12));
        let top = below.pose.translation.vector.z + below.size.z / 2.0;
        // The centre stays over the box below: a stable stack.
        let off = Vector3::new(
            uniform(rng, -0.3, 0.3) * (bw / 2.0),
            uniform(rng, -0.3, 0.3) * (bd / 2.0),
            top + size.z / 2.0,
        );
        let spin = below.pose.rotation * yaw(uniform(rng, -0.5, 0.5));
        items.push(Item { size, pose: at(off, spin), kind: Kind::Stacked, visible: true });
    }
    items
}

fn group_leaning(rng: &mut Rng) -> Vec<Item> {
    let (a, d, h) = (uniform(rng, 0.06, 0.15), uniform(rng, 0.06, 0.15), uniform(rng, 0.08, 0.2));
    let base = upright(Vector3::new(a, d, h), 0.0, Kind::Resting);
    let beta = uniform(rng, 15.0, 35.0) * PI / 180.0;
    let (sb, cb) = (libm::sin(beta), libm::cos(beta));
    let th = uniform(rng, 0.015, 0.04);
    let width = uniform(rng, 0.05, 0.15);
    let len = h / cb + uniform(rng, 0.02, 0.08);
    // The plank's +x face runs from its foot on the table through the base's top -x edge.
    let foot = Vector3::new(-a / 2.0 - h * sb / cb, 0.0, 0.0);
    let (x_axis, z_axis) = (Vector3::new(cb, 0.0, -sb), Vector3::new(sb, 0.0, cb));
    let center = foot - x_axis * (th / 2.0) + z_axis * (len / 2.0);
    let plank = Item {
        size: Vector3::new(th, width, len),
        pose: at(center, about_y(beta)),
        kind: Kind::Leaning,
        visible: true,
    };
    vec![base, plank]
}

fn group_hovering(rng: &mut Rng) -> Vec<Item> {
    let hidden = Vector3::new(uniform(rng, 0.04, 0.09), uniform(rng, 0.04, 0.09), uniform(rng, 0.03, 0.10));
    let size = Vector3::new(
        uniform(rng, hidden.x + 0.03, 0.18),
        uniform(rng, hidden.y + 0.03, 0.18),
        uniform(rng, 0.03, 0.12),
    );
    let support = Item { visible: false, ..upright(hidden, 0.0, Kind::Resting) };
    let mut top = upright(size, hidden.z, Kind::Hovering);
    top.pose.rotation = yaw(uniform(rng, -0.4, 0.4));
    vec![support, top]
}

/// A uniformly random rotation.
fn random_rotation(rng: &mut Rng) -> UnitQuaternion<f64> {
    loop {
        let q = Quaternion::new(rng.normal(), rng.normal(), rng.normal(), rng.normal());
        if q.norm() > 1e-6 {
            return UnitQuaternion::new_normalize(q);
        }
    }
}

/// Radius of a group's footprint around its origin.
fn radius(items: &[Item]) -> f64 {
    items.iter().flat_map(|it| it.obb().vertices()).map(|v| (v.x * v.x + v.y * v.y).sqrt()).fold(0.0, f64::max)
}

/// The camera looking at the table centre from distance `d`, elevation `e` and azimuth `a`.
fn camera(config: &SynthConfig, rng: &mut Rng) -> Camera {
    let d = uniform(rng, config.distance[0], config.distance[1]);
    let e = uniform(rng, config.elevation_deg[0], config.elevation_deg[1]) * PI / 180.0;
    let a = uniform(rng, config.azimuth_deg[0], config.azimuth_deg[1]) * PI / 180.0;
    let (ce, se, ca, sa) = (libm::cos(e), libm::sin(e), libm::cos(a), libm::sin(a));
    let pos = Vector3::new(d * ce * sa, -d * ce * ca, d * se);
    let forward = -pos / d;
    let right = forward.cross(&Vector3::z()).normalize();
    let down = forward.cross(&right);
    let r = Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[right, down, forward]));
    let q = UnitQuaternion::from_rotation_matrix(&r);
    let [w, h] = config.image;
    Camera {
        fx: config.focal,
        fy: config.focal,
        cx: w as f64 / 2.0,
        cy: h as f64 / 2.0,
        width: w,
        height: h,
        pose: Pose::from_isometry(&at(pos, q)),
        baseline: config.baseline,
    }
}

/// Keypoints on the faces of `item` that face the camera, projected with pixel noise.
fn keypoints(item: &Item, camera: &Camera, config: &SynthConfig, rng: &mut Rng) -> Vec<Keypoint> {
    let projector = camera.projector();
    let cam = Vector3::from(camera.pose.t);
    let h = item.size / 2.0;
    // Faces: axis k, sign s; area of the face; visible if its outward normal faces the camera.
    let mut faces = Vec::new();
    for k in 0..3 {
        for s in [-1.0, 1.0] {
            let normal = item.pose.rotation * (Vector3::ith(k, 1.0) * s);
            let center = item.pose * nalgebra::Point3::from(Vector3::ith(k, h[k] * s));
            if normal.dot(&(cam - center.coords)) > 0.0 {
                let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
                faces.push((k, s, item.size[k1] * item.size[k2]));
            }
        }
    }
    let total: f64 = faces.iter().map(|f| f.2).sum();
    let mut out = Vec::new();
    if faces.is_empty() || total <= 0.0 {
        return out;
    }
    let want = config.keypoints as usize;
    for _ in 0..want * 4 {
        if out.len() >= want {
            break;
        }
        let mut pick = rng.uniform() * total;
        let mut face = faces[faces.len() - 1];
        for f in &faces {
            if pick < f.2 {
                face = *f;
                break;
            }
            pick -= f.2;
        }
        let (k, s, _) = face;
        let mut m = Vector3::zeros();
        for j in 0..3 {
            m[j] = if j == k { h[j] * s } else { uniform(rng, -h[j], h[j]) };
        }
        let p = item.pose * nalgebra::Point3::from(m);
        let Some((left, right)) = projector.project_stereo(&p.coords) else { continue };
        let inside = |u: f64, v: f64| u >= 0.0 && v >= 0.0 && u < camera.width as f64 && v < camera.height as f64;
        let u = left.x + config.pixel_noise * rng.normal();
        let v = left.y + config.pixel_noise * rng.normal();
        let (ur, vr) = (right.x + config.pixel_noise * rng.normal(), right.y + config.pixel_noise * rng.normal());
        if !inside(u, v) {
            continue;
        }
        let image_right = (camera.baseline.is_some() && inside(ur, vr)).then(|| [round(ur, 1e3), round(vr, 1e3)]);
        out.push(Keypoint {
            model: [m.x, m.y, m.z].map(|c| round(c, 1e6)),
            image: [round(u, 1e3), round(v, 1e3)],
            image_right,
        });
    }
    out
}

fn round(v: f64, scale: f64) -> f64 {
    (v * scale).round() / scale
}

fn rounded(pose: &Isometry3<f64>) -> Pose {
    let p = Pose::from_isometry(pose);
    Pose { t: p.t.map(|v| round(v, 1e6)), q: p.q.map(|v| round(v, 1e9)) }
}

/// Why a scene could not be generated.
#[derive(Debug, Clone, PartialEq)]
pub enum SynthError {
    /// The configuration's JSON text does not parse, or is no object.
    Config(String),
    /// A setting of the configuration is out of its range: which, and what it must be.
    Setting(InvalidSetting),
    /// The forced hovering boxes or false estimates did not fit on the table.
    NoRoom(String),
}

impl std::fmt::Display for SynthError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SynthError::Config(m) => write!(f, "invalid synthetic scene configuration: {m}"),
            SynthError::Setting(e) => write!(f, "invalid synthetic scene configuration: {e}"),
            SynthError::NoRoom(m) => write!(f, "could not place the scene: {m}; use a larger area or fewer objects"),
        }
    }
}

impl std::error::Error for SynthError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            SynthError::Setting(e) => Some(e),
            _ => None,
        }
    }
}

/// Generates a scene with ground truth from `seed`.
pub fn generate(config: &SynthConfig, seed: u64) -> Result<Scene, SynthError> {
    config.validate().map_err(SynthError::Setting)?;
    let mut rng = Rng::seed(seed);
    let camera = camera(config, &mut rng);
    let target = config.min_objects + rng.below(config.max_objects - config.min_objects + 1);
    let forced_false = config.false_estimates.unwrap_or(0);
    let mut n_false = forced_false;
    if config.false_estimates.is_none() {
        for _ in 0..2 {
            if rng.uniform() < config.false_probability {
                n_false += 1;
            }
        }
    }
    let n_false = n_false.min(config.max_objects);
    let budget = target.max(n_false + config.hovering.unwrap_or(0) + (n_false > 0) as u32).min(config.max_objects);
    let (mut items, mut visible) = place_groups(config, budget, n_false, &mut rng);
    let placed_hovering = items.iter().filter(|i| i.kind == Kind::Hovering).count() as u32;
    if let Some(h) = config.hovering {
        if placed_hovering < h {
            return Err(SynthError::NoRoom(format!("placed {placed_hovering} of {h} hovering boxes")));
        }
    }
    let tol = Tolerances::default();
    let table = Table { size: config.table, thickness: super::scene::DEFAULT_TABLE_THICKNESS };
    let table_box = table.obb();
    let mut added_false = 0;
    for _ in 0..n_false {
        if visible >= config.max_objects {
            break;
        }
        if let Some(f) = false_estimate(&items, &table_box, &tol, &mut rng) {
            items.push(f);
            visible += 1;
            added_false += 1;
        }
    }
    if config.false_estimates.is_some_and(|n| added_false < n) {
        return Err(SynthError::NoRoom(format!("placed {added_false} of {n_false} false estimates")));
    }
    let (objects, hidden_objects) = observe(&items, &camera, config, &mut rng);
    let mut scene = Scene { table, camera, objects, hidden_objects };
    scene.camera.pose =
        Pose { t: scene.camera.pose.t.map(|v| round(v, 1e6)), q: scene.camera.pose.q.map(|v| round(v, 1e9)) };
    scene
        .validate()
        .map_err(|e| SynthError::NoRoom(format!("the generated scene is invalid ({e}); try another seed")))?;
    Ok(scene)
}

/// Places groups of boxes (resting, stacked, leaning, hovering) on the table until `budget`
/// visible boxes, less room for `n_false` false estimates, are placed or 40 groups did not
/// fit; returns the boxes and how many are visible.
fn place_groups(config: &SynthConfig, budget: u32, n_false: u32, rng: &mut Rng) -> (Vec<Item>, u32) {
    let mut items: Vec<Item> = Vec::new();
    let mut discs: Vec<(f64, f64, f64)> = Vec::new();
    let mut visible = 0u32;
    let mut hovering_left = config.hovering.unwrap_or(0);
    let mut failures = 0;
    // Leave room for the false estimates, and make sure they have an object to cut into.
    let reserve = |visible: u32| budget.saturating_sub(visible).saturating_sub(n_false);
    let has_target =
        |items: &[Item]| items.iter().any(|i| i.visible && matches!(i.kind, Kind::Resting | Kind::Stacked));
    while failures < 40 {
        let need_target = n_false > 0 && !has_target(&items);
        if reserve(visible) == 0 && !need_target {
            break;
        }
        let left = reserve(visible);
        let forced_hover = hovering_left > 0 && (left > 1 || !need_target);
        let group = if forced_hover {
            hovering_left -= 1;
            group_hovering(rng)
        } else if need_target && left <= 1 {
            group_resting(rng)
        } else {
            let mut w = config.group_weights;
            if config.hovering.is_some() {
                w[3] = 0.0;
            }
            if left < 2 {
                w[1] = 0.0;
                w[2] = 0.0;
            }
            if w.iter().sum::<f64>() <= 0.0 {
                w = [1.0, 0.0, 0.0, 0.0];
            }
            let mut pick = rng.uniform() * w.iter().sum::<f64>();
            let mut kind = 0;
            for (k, wk) in w.iter().enumerate() {
                if pick < *wk {
                    kind = k;
                    break;
                }
                pick -= wk;
            }
            match kind {
                0 => group_resting(rng),
                1 => group_stack(rng, left),
                2 => group_leaning(rng),
                _ => group_hovering(rng),
            }
        };
        let r = radius(&group);
        let (ax, ay) = (config.area[0] / 2.0 - r, config.area[1] / 2.0 - r);
        let mut placed = false;
        if ax > 0.0 && ay > 0.0 {
            for _ in 0..60 {
                let (x, y) = (uniform(rng, -ax, ax), uniform(rng, -ay, ay));
                if discs.iter().all(|&(u, v, s)| ((x - u) * (x - u) + (y - v) * (y - v)).sqrt() > r + s + 0.03) {
                    let place = at(Vector3::new(x, y, 0.0), yaw(uniform(rng, 0.0, 2.0 * PI)));
                    discs.push((x, y, r));
                    for mut it in group {
                        it.pose = place * it.pose;
                        visible += it.visible as u32;
                        items.push(it);
                    }
                    placed = true;
                    break;
                }
            }
        }
        if !placed {
            failures += 1;
            if forced_hover {
                // A forced hovering box that did not fit is retried.
                hovering_left += 1;
            }
        }
    }
    (items, visible)
}

/// What the sensor reports of the visible boxes: noisy poses and keypoints, with the truth;
/// and the hidden supports of hovering boxes.
fn observe(
    items: &[Item],
    camera: &Camera,
    config: &SynthConfig,
    rng: &mut Rng,
) -> (Vec<SceneObject>, Vec<HiddenObject>) {
    let mut objects = Vec::new();
    let mut hidden_objects = Vec::new();
    let mut count = 0;
    for (idx, it) in items.iter().enumerate() {
        if !it.visible {
            continue;
        }
        count += 1;
        let id = format!("o{count}");
        let kps = keypoints(it, camera, config, rng);
        let estimate = perturb(&it.pose, config.pose_noise_t, config.pose_noise_r, rng);
        if it.kind == Kind::Hovering {
            // The support generated just before it.
            if let Some(h) = items[..idx].iter().rev().find(|h| !h.visible) {
                hidden_objects.push(HiddenObject {
                    size: h.size.into(),
                    pose: rounded(&h.pose),
                    under: Some(id.clone()),
                });
            }
        }
        objects.push(SceneObject {
            id,
            size: it.size.map(|v| round(v, 1e6)).into(),
            pose: rounded(&estimate),
            keypoints: kps,
            truth: Some(Truth {
                hidden: it.kind == Kind::Hovering,
                false_estimate: it.kind == Kind::False,
                pose: config.record_poses.then(|| rounded(&it.pose)),
                kind: Some(it.kind.name().to_string()),
            }),
        });
    }
    (objects, hidden_objects)
}

/// A false estimate: a tilted box cutting 2 - 4 cm into a stable visible object and touching
/// nothing else.
fn false_estimate(items: &[Item], table: &Obb, tol: &Tolerances, rng: &mut Rng) -> Option<Item> {
    let targets: Vec<usize> = (0..items.len())
        .filter(|&i| items[i].visible && matches!(items[i].kind, Kind::Resting | Kind::Stacked))
        .collect();
    if targets.is_empty() {
        return None;
    }
    let min_tilt = libm::cos(20.0 * PI / 180.0);
    for _ in 0..200 {
        let target = &items[targets[rng.below(targets.len() as u32) as usize]];
        let size = Vector3::new(uniform(rng, 0.05, 0.14), uniform(rng, 0.05, 0.14), uniform(rng, 0.05, 0.14));
        let rotation = random_rotation(rng);
        let mut item = Item { size, pose: at(Vector3::zeros(), rotation), kind: Kind::False, visible: true };
        if item.obb().vertical_cos() > min_tilt {
            continue;
        }
        // A direction from the target's centre, upwards or sideways.
        let dir = Vector3::new(rng.normal(), rng.normal(), rng.normal().abs() + 0.3).normalize();
        let depth = uniform(rng, 0.02, 0.04);
        let t_obb = target.obb();
        let c0 = target.pose.translation.vector;
        // Bisection on the distance along `dir` for the wanted penetration depth.
        let (mut lo, mut hi) = (0.0, 1.0);
        let pen = |s: f64, item: &mut Item| {
            item.pose.translation.vector = c0 + dir * s;
            penetration(&item.obb(), &t_obb)
        };
        if pen(lo, &mut item) < depth || pen(hi, &mut item) > depth {
            continue;
        }
        for _ in 0..50 {
            let mid = (lo + hi) / 2.0;
            if pen(mid, &mut item) > depth {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        pen(lo, &mut item);
        let f = item.obb();
        let clear_of_table = relation(&f, table, tol) == Relation::Apart;
        let clear_of_others =
            items.iter().all(|other| std::ptr::eq(other, target) || relation(&f, &other.obb(), tol) == Relation::Apart);
        let only_cuts = relation(&f, &t_obb, tol) == Relation::Intersect;
        if clear_of_table && clear_of_others && only_cuts {
            return Some(item);
        }
    }
    None
}
