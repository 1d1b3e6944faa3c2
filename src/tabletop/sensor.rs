//! The likelihood `p(D|M)`: how well a pose explains what the camera saw (section 4.8).
//!
//! With matched keypoints, the likelihood is the Gaussian sensor model of eq. 4.4: each model
//! keypoint, moved by the pose and projected through the pinhole camera, should land on the
//! image point it was matched to, up to independent Gaussian errors of `sigma_x`, `sigma_y`
//! pixels (1 pixel in the dissertation's experiments):
//!
//! ```text
//! p(D|M) = prod_i N(x_i; x_i^psi, sigma_x) N(y_i; y_i^psi, sigma_y)          (4.4)
//! ```
//!
//! An object without keypoints has no image evidence; its likelihood is then a Gaussian on the
//! pose itself, centred on the estimate the scene gives:
//!
//! ```text
//! log p(D|M) = -|t - t0|^2 / (2 sigma_t^2) - theta^2 / (2 sigma_r^2)      (+ const)
//! ```
//!
//! where `theta` is the angle of the rotation between the pose and the estimate. It lets the
//! chain move a pose only as far as the knowledge (the prior of eq. 4.3) makes worthwhile:
//! typically the few millimetres that resolve an intersection of two stable objects.
//!
//! With a stereo camera, keypoints that give a right-image position contribute a second pair
//! of factors for the right image (the product of eq. 4.4 runs over the keypoints of both
//! images).
//!
//! Both are returned as logarithms. A model keypoint that the pose puts behind the camera
//! cannot be seen; it counts as a residual of [`BEHIND_CAMERA_RESIDUAL`] pixels in each
//! direction, far worse than any visible point, so the chain never prefers such poses.
//!
//! ```
//! use ksmcmc::tabletop::scene::{Camera, Keypoint, Pose};
//! use ksmcmc::tabletop::sensor::{keypoint_log_likelihood, SensorConfig};
//! use nalgebra::{Isometry3, Vector3};
//!
//! // A camera 1 m above the origin looking straight down (x right, y down, z forward).
//! let camera = Camera { fx: 500.0, fy: 500.0, cx: 320.0, cy: 240.0, width: 640, height: 480,
//!     pose: Pose { t: [0.0, 0.0, 1.0], q: [1.0, 0.0, 0.0, 0.0] }, baseline: None };
//! let projector = camera.projector();
//! // The model point at the object origin is seen at the principal point, 1 pixel off in x.
//! let kp = [Keypoint { model: [0.0, 0.0, 0.0], image: [321.0, 240.0], image_right: None }];
//! let config = SensorConfig::default();
//! let at_origin = keypoint_log_likelihood(&projector, &Isometry3::identity(), &kp, &config);
//! let two_mm = Isometry3::translation(0.002, 0.0, 0.0); // 1 px to the right: a perfect fit
//! let moved = keypoint_log_likelihood(&projector, &two_mm, &kp, &config);
//! assert!((moved - at_origin - 0.5).abs() < 1e-9); // eq. 4.4: exp(-1^2 / 2) less at the origin
//! ```

use super::scene::{Keypoint, Projector};
use crate::setting::{check, InvalidSetting};
use nalgebra::{Isometry3, Matrix6, Quaternion, Translation3, UnitQuaternion, Vector3, Vector6};
use serde::{Deserialize, Serialize};

/// The residual, in pixels in each direction, of a keypoint the pose puts behind the camera.
pub const BEHIND_CAMERA_RESIDUAL: f64 = 1.0e4;

/// Parameters of the likelihood.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SensorConfig {
    /// Standard deviation of keypoint positions in `x`, pixels (eq. 4.4; default 1).
    pub sigma_x: f64,
    /// Standard deviation of keypoint positions in `y`, pixels (eq. 4.4; default 1).
    pub sigma_y: f64,
    /// Without keypoints: standard deviation of the position around the estimate, metres
    /// (default 0.005).
    pub sigma_t: f64,
    /// Without keypoints: standard deviation of the rotation angle from the estimate, radians
    /// (default 0.035, 2 degrees).
    pub sigma_r: f64,
}

impl Default for SensorConfig {
    fn default() -> Self {
        SensorConfig { sigma_x: 1.0, sigma_y: 1.0, sigma_t: 0.005, sigma_r: 0.035 }
    }
}

impl SensorConfig {
    /// Checks that every deviation is positive and finite.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        for (name, v) in
            [("sigma_x", self.sigma_x), ("sigma_y", self.sigma_y), ("sigma_t", self.sigma_t), ("sigma_r", self.sigma_r)]
        {
            check(v.is_finite() && v > 0.0, name, v, "a positive number")?;
        }
        Ok(())
    }
}

/// `log p(D|M)` of eq. 4.4 for one object at `pose` (box frame to table frame) with matched
/// `keypoints`, over both images of a stereo pair where keypoints give both, including the
/// normalising constants.
pub fn keypoint_log_likelihood(
    projector: &Projector,
    pose: &Isometry3<f64>,
    keypoints: &[Keypoint],
    config: &SensorConfig,
) -> f64 {
    let (sx, sy) = (config.sigma_x, config.sigma_y);
    let norm = libm::log(std::f64::consts::TAU * sx * sy);
    let (ix, iy) = (0.5 / (sx * sx), 0.5 / (sy * sy));
    let mut total = 0.0;
    let far = BEHIND_CAMERA_RESIDUAL;
    for kp in keypoints {
        let p = pose * nalgebra::Point3::from(Vector3::from(kp.model));
        match projector.project_stereo(&p.coords) {
            Some((left, right)) => {
                let (dx, dy) = (left.x - kp.image[0], left.y - kp.image[1]);
                total -= dx * dx * ix + dy * dy * iy + norm;
                if let Some(r) = kp.image_right {
                    let (dx, dy) = (right.x - r[0], right.y - r[1]);
                    total -= dx * dx * ix + dy * dy * iy + norm;
                }
            }
            None => {
                let views = 1.0 + kp.image_right.is_some() as u8 as f64;
                total -= views * (far * far * (ix + iy) + norm);
            }
        }
    }
    total
}

/// The rotation by rotation vector `w` (axis times angle, radians).
pub fn rotation_from_vector(w: &Vector3<f64>) -> UnitQuaternion<f64> {
    let theta = w.norm();
    if theta == 0.0 {
        return UnitQuaternion::identity();
    }
    let s = libm::sin(theta / 2.0) / theta;
    UnitQuaternion::new_normalize(Quaternion::new(libm::cos(theta / 2.0), w.x * s, w.y * s, w.z * s))
}

/// A pose moved by a tangent vector `d`: `d[0..3]` added to the translation (table frame),
/// `d[3..6]` a rotation vector applied in the table frame about the box centre.
pub fn retract(pose: &Isometry3<f64>, d: &Vector6<f64>) -> Isometry3<f64> {
    let t = pose.translation.vector + Vector3::new(d[0], d[1], d[2]);
    let r = rotation_from_vector(&Vector3::new(d[3], d[4], d[5])) * pose.rotation;
    Isometry3::from_parts(Translation3::from(t), r)
}

/// The Fisher information of eq. 4.4 about the pose, `J^T J` for the residuals of all
/// keypoints scaled by their deviations, with `J` their derivative along the six tangent
/// directions of [`retract`] (central differences). Its inverse is the covariance of the pose
/// that the keypoints determine: tight across the line of sight, loose along it.
pub fn keypoint_information(
    projector: &Projector,
    pose: &Isometry3<f64>,
    keypoints: &[Keypoint],
    config: &SensorConfig,
) -> Matrix6<f64> {
    let residuals = |p: &Isometry3<f64>, out: &mut Vec<f64>| {
        out.clear();
        for kp in keypoints {
            let q = p * nalgebra::Point3::from(Vector3::from(kp.model));
            match projector.project_stereo(&q.coords) {
                Some((l, r)) => {
                    out.push(l.x / config.sigma_x);
                    out.push(l.y / config.sigma_y);
                    if kp.image_right.is_some() {
                        out.push(r.x / config.sigma_x);
                        out.push(r.y / config.sigma_y);
                    }
                }
                None => out.extend([0.0; 4].iter().take(2 + 2 * kp.image_right.is_some() as usize)),
            }
        }
    };
    let h = [1e-6, 1e-6, 1e-6, 1e-6, 1e-6, 1e-6];
    let (mut plus, mut minus) = (Vec::new(), Vec::new());
    let mut columns: Vec<Vec<f64>> = Vec::with_capacity(6);
    for k in 0..6 {
        let mut d = Vector6::zeros();
        d[k] = h[k];
        residuals(&retract(pose, &d), &mut plus);
        residuals(&retract(pose, &-d), &mut minus);
        columns.push(plus.iter().zip(&minus).map(|(a, b)| (a - b) / (2.0 * h[k])).collect());
    }
    Matrix6::from_fn(|a, b| columns[a].iter().zip(&columns[b]).map(|(x, y)| x * y).sum())
}

/// The angle of the rotation between two unit quaternions, radians in `[0, pi]`.
pub fn rotation_angle(a: &UnitQuaternion<f64>, b: &UnitQuaternion<f64>) -> f64 {
    let d = a.inverse() * b;
    let q = d.quaternion();
    2.0 * libm::atan2(q.imag().norm(), q.w.abs())
}

/// The likelihood of an object without keypoints: a Gaussian on its pose around the estimate
/// `estimate` (see the module documentation), without its normalising constant.
pub fn pose_log_likelihood(pose: &Isometry3<f64>, estimate: &Isometry3<f64>, config: &SensorConfig) -> f64 {
    let dt = (pose.translation.vector - estimate.translation.vector).norm_squared();
    let theta = rotation_angle(&pose.rotation, &estimate.rotation);
    -dt / (2.0 * config.sigma_t * config.sigma_t) - theta * theta / (2.0 * config.sigma_r * config.sigma_r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_angle_of_a_quarter_turn() {
        let a = UnitQuaternion::identity();
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let b = UnitQuaternion::new_normalize(nalgebra::Quaternion::new(h, 0.0, 0.0, h));
        assert!((rotation_angle(&a, &b) - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert!(rotation_angle(&b, &b).abs() < 1e-7);
    }

    #[test]
    fn pose_likelihood_is_a_gaussian() {
        let c = SensorConfig::default();
        let e = Isometry3::identity();
        let p = Isometry3::translation(c.sigma_t, 0.0, 0.0);
        assert!((pose_log_likelihood(&p, &e, &c) + 0.5).abs() < 1e-12);
        assert_eq!(pose_log_likelihood(&e, &e, &c), 0.0);
    }
}
