//! The input: a table, a camera and estimated object poses (`scene.json`).
//!
//! # Schema
//!
//! All lengths are metres, angles radians, quaternions `[qx, qy, qz, qw]` (scalar last).
//! Poses are given in the *table frame*: the table top is the plane `z = 0` with `z` up, its
//! centre at the origin, its sides along `x` and `y`.
//!
//! ```text
//! {
//!   "table":  { "size": [sx, sy],                  // table top [-sx/2, sx/2] x [-sy/2, sy/2]
//!               "thickness": 0.05 },               // optional, default 0.05: the table is a box
//!   "camera": { "fx": f, "fy": f, "cx": u0, "cy": v0, "width": w, "height": h,
//!               "pose": { "t": [x, y, z], "q": [qx, qy, qz, qw] },
//!               "baseline": 0.12 },                // optional: a rectified stereo pair
//!   "objects": [
//!     { "id": "cup",                               // unique, not "table"
//!       "size": [sx, sy, sz],                      // full extents of the oriented box
//!       "pose": { "t": [x, y, z], "q": [...] },    // estimated pose of the box centre
//!       "keypoints": [                             // optional matched keypoints
//!         { "model": [x, y, z],                    // in the box frame (origin at its centre)
//!           "image": [u, v],                       // where the camera saw it, pixels
//!           "image_right": [u, v] } ],             // optional: in the right image
//!       "truth": { "hidden": false,                // optional ground truth, for evaluation:
//!                  "false": false,                 //   hidden object under it? false estimate?
//!                  "pose": { ... },                //   optional true pose
//!                  "kind": "resting" } }           //   optional free-form label
//!   ],
//!   "hidden_objects": [                            // optional, informative only: boxes the
//!     { "size": [...], "pose": {...}, "under": "cup" } ]   // camera did not see
//! }
//! ```
//!
//! The camera pose maps camera coordinates to table coordinates, with the usual computer
//! vision axes: `x` right, `y` down, `z` forward (the optical axis). A point `p` of the table
//! frame is seen at pixel `u = fx * x / z + cx`, `v = fy * y / z + cy` where `(x, y, z)` are
//! its camera coordinates (the pinhole model of section 4.8).
//!
//! The dissertation's sensor is a stereo camera, and eq. 4.4 runs over the keypoints of both
//! images. A `baseline` makes the camera the left one of a rectified pair: the right camera
//! sits `baseline` metres further along the left camera's `x` axis, with the same intrinsics,
//! and sees the point at `u - fx * baseline / z`, same `v`. Keypoints may then give their
//! right-image position too; the second view fixes the depth that one view leaves uncertain.
//!
//! Unknown fields are errors (a misspelt `"keypoint"` would otherwise silently drop the data).
//!
//! # Validation
//!
//! [`Scene::from_json`] parses and validates; [`Scene::validate`] checks a scene built in code.
//! Every problem is a [`SceneError`] naming the field at fault:
//!
//! * every number must be finite and at most [`MAX_MAGNITUDE`] in magnitude; sizes, the table
//!   thickness, the focal lengths and the stereo baseline positive;
//!   the image at least 1 x 1 pixel;
//! * quaternions are normalised when their norm is within [`QUATERNION_TOLERANCE`] of 1
//!   (rounding in files written with few digits); others, and the zero quaternion, are
//!   rejected, since a scaled quaternion usually means the fields are in the wrong order or
//!   are not a quaternion at all;
//! * the camera must be above the table top (`z > 0`), and every object's centre in front of
//!   it: a camera below the table or an object behind the camera means the camera pose is
//!   inverted or in another frame;
//! * an object must reach above the table top: an object entirely inside the table cannot have
//!   been seen. An object that only dips into the table is accepted; the analysis reads it as
//!   intersecting the table (evidence of a false estimate);
//! * ids must be unique, non-empty and not `"table"`, which names the table in the graph;
//! * at most [`MAX_OBJECTS`] objects, in at most [`MAX_SCENE_JSON_BYTES`] of text.
//!
//! ```
//! use ksmcmc::tabletop::scene::{Scene, SceneError};
//!
//! let json = r#"{
//!   "table": { "size": [1.2, 0.8] },
//!   "camera": { "fx": 600, "fy": 600, "cx": 320, "cy": 240, "width": 640, "height": 480,
//!               "pose": { "t": [0, -0.8, 0.6], "q": [-0.9, 0, 0, 0.42] } },
//!   "objects": [ { "id": "box", "size": [0.1, 0.1, 0.2],
//!                  "pose": { "t": [0, 0, 0.1], "q": [0, 0, 0, 1] } } ] }"#;
//! let scene = Scene::from_json(json).unwrap();
//! assert_eq!(scene.objects[0].id, "box");
//!
//! let bad = json.replace("[0.1, 0.1, 0.2]", "[0.1, 0, 0.2]");
//! let err = Scene::from_json(&bad).unwrap_err();
//! assert!(matches!(err, SceneError::BadNumber { .. }));
//! assert!(err.to_string().contains("objects[0] (\"box\").size"));
//! ```

use super::geometry::Obb;
use nalgebra::{Isometry3, Matrix3, Quaternion, Translation3, UnitQuaternion, Vector2, Vector3};
use serde::{Deserialize, Serialize};

/// Most objects a scene may hold. The knowledge base grounds every pair of objects, so the
/// work per iteration grows with the square of the count.
pub const MAX_OBJECTS: usize = 64;

/// Quaternions whose norm differs from 1 by at most this are accepted (and normalised where
/// used, see [`Pose::rotation`]); others are rejected.
pub const QUATERNION_TOLERANCE: f64 = 0.01;

/// The largest magnitude of any number in a scene (metres, pixels): beyond it, squares and
/// products of coordinates would lose all precision.
pub const MAX_MAGNITUDE: f64 = 1e6;

/// Longest `scene.json` text read, bytes (1 MiB; [`MAX_OBJECTS`] objects take a few tens of KB).
pub const MAX_SCENE_JSON_BYTES: usize = 1 << 20;

/// The default table thickness, metres.
pub const DEFAULT_TABLE_THICKNESS: f64 = 0.05;

/// A rigid pose: translation and rotation quaternion `[qx, qy, qz, qw]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pose {
    /// Translation, metres.
    pub t: [f64; 3],
    /// Rotation as a unit quaternion, scalar last.
    pub q: [f64; 4],
}

impl Pose {
    /// The identity pose moved to `t`.
    pub fn at(t: [f64; 3]) -> Pose {
        Pose { t, q: [0.0, 0.0, 0.0, 1.0] }
    }

    /// The rotation, from the quaternion normalised (the identity for a zero quaternion, which
    /// validation rejects).
    pub fn rotation(&self) -> UnitQuaternion<f64> {
        let [x, y, z, w] = self.q;
        let q = Quaternion::new(w, x, y, z);
        if q.norm() > 0.0 {
            UnitQuaternion::new_normalize(q)
        } else {
            UnitQuaternion::identity()
        }
    }

    /// The pose as an isometry.
    pub fn isometry(&self) -> Isometry3<f64> {
        Isometry3::from_parts(Translation3::new(self.t[0], self.t[1], self.t[2]), self.rotation())
    }

    /// The pose of an isometry.
    pub fn from_isometry(iso: &Isometry3<f64>) -> Pose {
        let q = iso.rotation.quaternion();
        let t = iso.translation.vector;
        Pose { t: [t.x, t.y, t.z], q: [q.i, q.j, q.k, q.w] }
    }
}

/// The table.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Table {
    /// Size of the top, `[sx, sy]`, centred at the origin.
    pub size: [f64; 2],
    /// Thickness of the table box below the top (default [`DEFAULT_TABLE_THICKNESS`]).
    #[serde(default = "default_thickness")]
    pub thickness: f64,
}

fn default_thickness() -> f64 {
    DEFAULT_TABLE_THICKNESS
}

impl Table {
    /// The table as a box.
    pub fn obb(&self) -> Obb {
        Obb::table(self.size, self.thickness)
    }
}

/// A pinhole camera and its pose in the table frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    /// Focal length in `x`, pixels.
    pub fx: f64,
    /// Focal length in `y`, pixels.
    pub fy: f64,
    /// Principal point `x`, pixels.
    pub cx: f64,
    /// Principal point `y`, pixels.
    pub cy: f64,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Camera to table: the camera centre and orientation in the table frame (`x` right, `y`
    /// down, `z` forward).
    pub pose: Pose,
    /// For a rectified stereo pair: the distance of the right camera from this (left) one
    /// along its `x` axis, metres. The right camera has the same intrinsics and orientation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub baseline: Option<f64>,
}

/// The smallest depth in front of the camera (metres) at which a point is projected.
pub const NEAR: f64 = 1e-3;

impl Camera {
    /// The rotation from table to camera coordinates and the camera centre.
    fn frame(&self) -> (Matrix3<f64>, Vector3<f64>) {
        let r = *self.pose.rotation().to_rotation_matrix().matrix();
        (r.transpose(), Vector3::from(self.pose.t))
    }

    /// A projector for points in the table frame.
    pub fn projector(&self) -> Projector {
        let (rot, center) = self.frame();
        Projector {
            rot,
            center,
            fx: self.fx,
            fy: self.fy,
            cx: self.cx,
            cy: self.cy,
            baseline: self.baseline.unwrap_or(0.0),
        }
    }
}

/// Projects table-frame points into the image (the pinhole model of section 4.8).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projector {
    /// Table to camera rotation.
    pub rot: Matrix3<f64>,
    /// Camera centre in the table frame.
    pub center: Vector3<f64>,
    /// Focal length in `x`.
    pub fx: f64,
    /// Focal length in `y`.
    pub fy: f64,
    /// Principal point `x`.
    pub cx: f64,
    /// Principal point `y`.
    pub cy: f64,
    /// Stereo baseline, metres (0 without a right camera).
    pub baseline: f64,
}

impl Projector {
    /// Camera coordinates of a table-frame point.
    #[inline]
    pub fn to_camera(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.rot * (p - self.center)
    }

    /// The pixel where a table-frame point is seen; `None` when it is not in front of the
    /// camera (depth below [`NEAR`]).
    #[inline]
    pub fn project(&self, p: &Vector3<f64>) -> Option<Vector2<f64>> {
        let c = self.to_camera(p);
        (c.z >= NEAR).then(|| Vector2::new(self.fx * c.x / c.z + self.cx, self.fy * c.y / c.z + self.cy))
    }

    /// Both pixels of a table-frame point: in this (left) camera and in the right camera of the
    /// stereo pair, `baseline` further along `x` (rectified: same row, shifted column).
    #[inline]
    pub fn project_stereo(&self, p: &Vector3<f64>) -> Option<(Vector2<f64>, Vector2<f64>)> {
        let c = self.to_camera(p);
        if c.z < NEAR {
            return None;
        }
        let (u, v) = (self.fx * c.x / c.z + self.cx, self.fy * c.y / c.z + self.cy);
        Some((Vector2::new(u, v), Vector2::new(u - self.fx * self.baseline / c.z, v)))
    }
}

/// A model keypoint matched to an image point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Keypoint {
    /// Position in the object's box frame, metres.
    pub model: [f64; 3],
    /// Where it was seen in the image, pixels.
    pub image: [f64; 2],
    /// Where it was seen in the right image of a stereo pair, pixels (needs
    /// `camera.baseline`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub image_right: Option<[f64; 2]>,
}

/// Ground truth of one object, for evaluation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Truth {
    /// An unseen object lies under this one.
    pub hidden: bool,
    /// This estimate is false: no such object is there.
    #[serde(rename = "false")]
    pub false_estimate: bool,
    /// The true pose, if known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pose: Option<Pose>,
    /// A free-form label of the configuration (the generator writes `resting`, `stacked`,
    /// `leaning`, `hovering`, `false`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<String>,
}

/// One estimated object.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneObject {
    /// Unique name.
    pub id: String,
    /// Full extents of its oriented box, metres.
    pub size: [f64; 3],
    /// Estimated pose of the box centre in the table frame.
    pub pose: Pose,
    /// Matched keypoints (optional).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub keypoints: Vec<Keypoint>,
    /// Ground truth (optional).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub truth: Option<Truth>,
}

impl SceneObject {
    /// The object's box at pose `pose`.
    pub fn obb_at(&self, pose: &Isometry3<f64>) -> Obb {
        Obb::new(pose.translation.vector, pose.rotation, Vector3::from(self.size))
    }

    /// The object's box at its estimated pose.
    pub fn obb(&self) -> Obb {
        self.obb_at(&self.pose.isometry())
    }
}

/// An object the camera did not see (recorded by the generator; the analysis ignores it).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HiddenObject {
    /// Full extents, metres.
    pub size: [f64; 3],
    /// Pose of its centre.
    pub pose: Pose,
    /// The id of the object it holds up.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub under: Option<String>,
}

/// A table-top scene: the input of the analysis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// The table.
    pub table: Table,
    /// The camera.
    pub camera: Camera,
    /// The estimated objects.
    pub objects: Vec<SceneObject>,
    /// Unseen objects (informative; ignored by the analysis).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hidden_objects: Vec<HiddenObject>,
}

/// Why a scene was refused.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum SceneError {
    /// Not valid JSON, or not the schema (a missing field, a wrong type, an unknown field).
    Json {
        /// What serde_json said.
        message: String,
        /// Line, 1-based (0 if unknown).
        line: usize,
        /// Column, 1-based (0 if unknown).
        column: usize,
    },
    /// A number that is not finite, or out of its range (a size that is zero or negative).
    BadNumber {
        /// The field, e.g. `objects[2] ("cup").size`.
        field: String,
        /// The value.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
    /// A quaternion of norm (close to) zero.
    ZeroQuaternion {
        /// The field.
        field: String,
    },
    /// A quaternion whose norm is not within [`QUATERNION_TOLERANCE`] of 1.
    NotUnitQuaternion {
        /// The field.
        field: String,
        /// Its norm.
        norm: f64,
    },
    /// The camera is not above the table top.
    CameraBelowTable {
        /// Its height.
        z: f64,
    },
    /// An object's centre is behind the camera.
    ObjectBehindCamera {
        /// The object.
        id: String,
        /// Depth of its centre along the optical axis.
        depth: f64,
    },
    /// An object lies entirely inside the table.
    ObjectInsideTable {
        /// The object.
        id: String,
        /// Height of its highest point.
        top: f64,
    },
    /// An id that is empty, reserved or repeated.
    BadId {
        /// The id.
        id: String,
        /// Why.
        reason: &'static str,
    },
    /// A keypoint gives a right-image position but the camera is not a stereo pair.
    NoBaseline {
        /// The keypoint field.
        field: String,
    },
    /// More than [`MAX_OBJECTS`] objects.
    TooManyObjects {
        /// How many.
        count: usize,
    },
}

impl std::fmt::Display for SceneError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SceneError::Json { message, .. } => write!(f, "not a valid scene: {message}"),
            SceneError::BadNumber { field, value, expected } => {
                write!(f, "{field} is {value}, but must be {expected}")
            }
            SceneError::ZeroQuaternion { field } => {
                write!(f, "{field} is the zero quaternion, which is no rotation; use [0, 0, 0, 1] for none")
            }
            SceneError::NotUnitQuaternion { field, norm } => write!(
                f,
                "{field} has norm {norm}, not 1: a rotation quaternion [qx, qy, qz, qw] must be a unit \
                 quaternion (norms within {QUATERNION_TOLERANCE} of 1 are normalised)"
            ),
            SceneError::CameraBelowTable { z } => write!(
                f,
                "the camera is at height {z} m, not above the table top (z = 0): camera.pose must give \
                 the camera in the table frame, z up"
            ),
            SceneError::ObjectBehindCamera { id, depth } => write!(
                f,
                "object {id:?} is behind the camera (depth {depth} m); camera.pose maps camera to table \
                 coordinates with x right, y down, z forward: check that it is not inverted"
            ),
            SceneError::ObjectInsideTable { id, top } => write!(
                f,
                "object {id:?} lies entirely inside the table (its highest point is at z = {top} m); poses \
                 are in the table frame, whose top is the plane z = 0 with z up"
            ),
            SceneError::BadId { id, reason } => write!(f, "object id {id:?} {reason}"),
            SceneError::NoBaseline { field } => write!(
                f,
                "{field} is a right-image position, but camera.baseline is missing: give the stereo \
                 baseline in metres, or leave image_right out"
            ),
            SceneError::TooManyObjects { count } => {
                write!(f, "the scene has {count} objects; at most {MAX_OBJECTS} are supported")
            }
        }
    }
}

impl std::error::Error for SceneError {}

fn check_finite(field: &dyn Fn() -> String, values: &[f64]) -> Result<(), SceneError> {
    match values.iter().find(|v| !(v.is_finite() && v.abs() <= MAX_MAGNITUDE)) {
        Some(&value) => {
            Err(SceneError::BadNumber { field: field(), value, expected: "a finite number of magnitude at most 1e6" })
        }
        None => Ok(()),
    }
}

fn check_positive(field: &dyn Fn() -> String, values: &[f64]) -> Result<(), SceneError> {
    check_finite(field, values)?;
    match values.iter().find(|v| **v <= 0.0) {
        Some(&value) => Err(SceneError::BadNumber { field: field(), value, expected: "positive" }),
        None => Ok(()),
    }
}

/// Checks a pose and normalises its quaternion.
fn check_pose(pose: &mut Pose, field: &dyn Fn() -> String) -> Result<(), SceneError> {
    check_finite(&|| format!("{}.t", field()), &pose.t)?;
    check_finite(&|| format!("{}.q", field()), &pose.q)?;
    let norm = pose.q.iter().map(|v| v * v).sum::<f64>().sqrt();
    if norm < 1e-12 {
        return Err(SceneError::ZeroQuaternion { field: format!("{}.q", field()) });
    }
    if (norm - 1.0).abs() > QUATERNION_TOLERANCE {
        return Err(SceneError::NotUnitQuaternion { field: format!("{}.q", field()), norm });
    }
    // Quaternions are normalised again wherever they are used ([`Pose::rotation`]); the
    // stored value changes only when it is visibly off, so that a scene written with a few
    // digits reads back as the same scene.
    if (norm - 1.0).abs() > 1e-6 {
        pose.q = pose.q.map(|v| v / norm);
    }
    Ok(())
}

impl Scene {
    /// Parses and validates a scene (see the module documentation).
    pub fn from_json(text: &str) -> Result<Scene, SceneError> {
        if text.len() > MAX_SCENE_JSON_BYTES {
            return Err(SceneError::Json {
                message: format!(
                    "the text is {} bytes, over the limit of {MAX_SCENE_JSON_BYTES} bytes for a scene \
                     (at most {MAX_OBJECTS} objects)",
                    text.len()
                ),
                line: 0,
                column: 0,
            });
        }
        let mut scene: Scene = serde_json::from_str(text).map_err(|e| SceneError::Json {
            message: e.to_string(),
            line: e.line(),
            column: e.column(),
        })?;
        scene.validate()?;
        Ok(scene)
    }

    /// The scene as pretty-printed JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Checks every field (see the module documentation) and normalises near-unit quaternions.
    pub fn validate(&mut self) -> Result<(), SceneError> {
        let t = &self.table;
        check_positive(&|| "table.size".into(), &t.size)?;
        check_positive(&|| "table.thickness".into(), &[t.thickness])?;
        let c = &mut self.camera;
        check_positive(&|| "camera.fx".into(), &[c.fx])?;
        check_positive(&|| "camera.fy".into(), &[c.fy])?;
        check_finite(&|| "camera.cx".into(), &[c.cx])?;
        check_finite(&|| "camera.cy".into(), &[c.cy])?;
        for (name, v) in [("camera.width", c.width), ("camera.height", c.height)] {
            if v == 0 {
                return Err(SceneError::BadNumber { field: name.into(), value: 0.0, expected: "at least 1 pixel" });
            }
        }
        check_pose(&mut c.pose, &|| "camera.pose".into())?;
        if let Some(b) = c.baseline {
            check_positive(&|| "camera.baseline".into(), &[b])?;
        }
        let stereo = c.baseline.is_some();
        if c.pose.t[2] <= 0.0 {
            return Err(SceneError::CameraBelowTable { z: c.pose.t[2] });
        }
        if self.objects.len() > MAX_OBJECTS {
            return Err(SceneError::TooManyObjects { count: self.objects.len() });
        }
        let projector = self.camera.projector();
        let mut ids = std::collections::HashSet::new();
        for (i, o) in self.objects.iter_mut().enumerate() {
            let id = o.id.clone();
            let name = |field: &str| format!("objects[{i}] ({id:?}).{field}");
            if o.id.trim().is_empty() {
                return Err(SceneError::BadId { id: o.id.clone(), reason: "is empty" });
            }
            if o.id == "table" {
                return Err(SceneError::BadId { id: o.id.clone(), reason: "is reserved for the table" });
            }
            if !ids.insert(o.id.clone()) {
                return Err(SceneError::BadId { id: o.id.clone(), reason: "is used twice" });
            }
            check_positive(&|| name("size"), &o.size)?;
            check_pose(&mut o.pose, &|| name("pose"))?;
            for (k, kp) in o.keypoints.iter().enumerate() {
                check_finite(&|| name(&format!("keypoints[{k}].model")), &kp.model)?;
                check_finite(&|| name(&format!("keypoints[{k}].image")), &kp.image)?;
                if let Some(right) = kp.image_right {
                    let field = || name(&format!("keypoints[{k}].image_right"));
                    check_finite(&field, &right)?;
                    if !stereo {
                        return Err(SceneError::NoBaseline { field: field() });
                    }
                }
            }
            if let Some(truth) = &mut o.truth {
                if let Some(p) = &mut truth.pose {
                    check_pose(p, &|| name("truth.pose"))?;
                }
            }
            let top = o.obb().max_z();
            if top <= 0.0 {
                return Err(SceneError::ObjectInsideTable { id: o.id.clone(), top });
            }
            let depth = projector.to_camera(&Vector3::from(o.pose.t)).z;
            if depth <= 0.0 {
                return Err(SceneError::ObjectBehindCamera { id: o.id.clone(), depth });
            }
        }
        for (i, h) in self.hidden_objects.iter_mut().enumerate() {
            check_positive(&|| format!("hidden_objects[{i}].size"), &h.size)?;
            check_pose(&mut h.pose, &|| format!("hidden_objects[{i}].pose"))?;
        }
        Ok(())
    }
}
