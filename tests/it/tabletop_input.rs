//! Bad table-top input: every kind of invalid scene gives a typed error whose message names
//! the field and says what to do, odd but valid scenes are handled as documented, and random
//! corruption never panics.

use ksmcmc::mcmc::Rng;
use ksmcmc::render::tabletop::{draw_graph, draw_view, marks, ViewOptions};
use ksmcmc::tabletop::scene::{Pose, Scene, SceneError, SceneObject, MAX_OBJECTS};
use ksmcmc::tabletop::synth::{generate, SynthConfig};
use ksmcmc::tabletop::{ChainConfig, Decision, TabletopChain};

fn base() -> Scene {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/samples/tabletop/fig-4-9.json")).unwrap();
    Scene::from_json(&text).unwrap()
}

fn json_of(s: &Scene) -> serde_json::Value {
    serde_json::from_str(&s.to_json()).unwrap()
}

/// Parses a modified copy of the base scene's JSON.
fn parse_with(edit: impl FnOnce(&mut serde_json::Value)) -> Result<Scene, SceneError> {
    let mut v = json_of(&base());
    edit(&mut v);
    Scene::from_json(&v.to_string())
}

fn validate_with(edit: impl FnOnce(&mut Scene)) -> Result<(), SceneError> {
    let mut s = base();
    edit(&mut s);
    s.validate()
}

fn message(e: &SceneError) -> String {
    e.to_string()
}

#[test]
fn sizes_must_be_positive() {
    for bad in [0.0, -0.1] {
        let e = parse_with(|v| v["objects"][1]["size"][2] = bad.into()).unwrap_err();
        assert!(matches!(e, SceneError::BadNumber { value, .. } if value == bad), "{e:?}");
        let m = message(&e);
        assert!(m.contains("objects[1] (\"2\").size") && m.contains("positive"), "{m}");
    }
    let e = parse_with(|v| v["table"]["size"][0] = 0.into()).unwrap_err();
    assert!(message(&e).contains("table.size"));
    let e = parse_with(|v| v["table"]["thickness"] = (-0.01).into()).unwrap_err();
    assert!(message(&e).contains("table.thickness"));
    let e = parse_with(|v| v["camera"]["fx"] = 0.into()).unwrap_err();
    assert!(message(&e).contains("camera.fx"));
    let e = parse_with(|v| v["camera"]["width"] = 0.into()).unwrap_err();
    assert!(message(&e).contains("camera.width") && message(&e).contains("at least 1 pixel"));
    let e = parse_with(|v| v["camera"]["baseline"] = (-0.1).into()).unwrap_err();
    assert!(message(&e).contains("camera.baseline"));
}

#[test]
fn numbers_must_be_finite_and_reasonable() {
    for (what, edit) in [
        (
            "objects[0] (\"1\").pose.t",
            Box::new(|s: &mut Scene| s.objects[0].pose.t[0] = f64::NAN) as Box<dyn FnOnce(&mut Scene)>,
        ),
        ("objects[2] (\"3\").pose.q", Box::new(|s: &mut Scene| s.objects[2].pose.q[3] = f64::INFINITY)),
        ("camera.cx", Box::new(|s: &mut Scene| s.camera.cx = f64::NAN)),
        ("camera.pose.t", Box::new(|s: &mut Scene| s.camera.pose.t[2] = f64::NEG_INFINITY)),
        ("table.size", Box::new(|s: &mut Scene| s.table.size[1] = f64::NAN)),
        ("objects[0] (\"1\").size", Box::new(|s: &mut Scene| s.objects[0].size[0] = 1e7)),
    ] {
        let e = validate_with(edit).unwrap_err();
        assert!(matches!(e, SceneError::BadNumber { .. }), "{e:?}");
        assert!(message(&e).contains(what), "{what}: {}", message(&e));
    }
    // JSON has no NaN; numbers too large for a double are parse errors with a position.
    for text in [r#"NaN"#, "1e999"] {
        let mut v = base().to_json();
        v = v.replacen("0.05", text, 1);
        let e = Scene::from_json(&v).unwrap_err();
        match e {
            SceneError::Json { line, .. } => assert!(line > 0),
            SceneError::BadNumber { .. } => {}
            other => panic!("{other:?}"),
        }
    }
}

#[test]
fn missing_and_unknown_fields_are_named() {
    let e = parse_with(|v| {
        v.as_object_mut().unwrap().remove("camera");
    })
    .unwrap_err();
    assert!(matches!(e, SceneError::Json { .. }));
    assert!(message(&e).contains("missing field `camera`"), "{}", message(&e));
    let e = parse_with(|v| {
        v["objects"][0].as_object_mut().unwrap().remove("size");
    })
    .unwrap_err();
    assert!(message(&e).contains("missing field `size`"), "{}", message(&e));
    let e = parse_with(|v| v["objects"][0]["keypoint"] = serde_json::json!([])).unwrap_err();
    assert!(message(&e).contains("unknown field `keypoint`"), "{}", message(&e));
    let e = Scene::from_json("{ not json").unwrap_err();
    assert!(matches!(e, SceneError::Json { line: 1, .. }), "{e:?}");
    assert!(Scene::from_json("").is_err());
    let e = parse_with(|v| v["objects"][0]["size"] = serde_json::json!([0.1, 0.1])).unwrap_err();
    assert!(matches!(e, SceneError::Json { .. }), "{e:?}");
}

#[test]
fn quaternions_zero_far_from_unit_and_near_unit() {
    let e = parse_with(|v| v["objects"][0]["pose"]["q"] = serde_json::json!([0, 0, 0, 0])).unwrap_err();
    assert!(matches!(e, SceneError::ZeroQuaternion { .. }));
    assert!(message(&e).contains("[0, 0, 0, 1]"), "{}", message(&e));
    let e = parse_with(|v| v["camera"]["pose"]["q"] = serde_json::json!([0, 0, 0, 2])).unwrap_err();
    assert!(matches!(e, SceneError::NotUnitQuaternion { norm, .. } if (norm - 2.0).abs() < 1e-12), "{e:?}");
    assert!(message(&e).contains("camera.pose.q"));
    // Within 1 % of unit: accepted and normalised.
    let s = parse_with(|v| v["objects"][0]["pose"]["q"] = serde_json::json!([0, 0, 0.6024, 0.8032])).unwrap();
    let q = s.objects[0].pose.q;
    assert!((q.iter().map(|v| v * v).sum::<f64>().sqrt() - 1.0).abs() < 1e-12);
    assert!((q[2] - 0.6).abs() < 1e-12 && (q[3] - 0.8).abs() < 1e-12);
}

#[test]
fn geometry_that_cannot_have_been_seen() {
    // An object entirely inside the table.
    let e = validate_with(|s| s.objects[0].pose.t[2] = -0.07).unwrap_err();
    assert!(matches!(e, SceneError::ObjectInsideTable { .. }), "{e:?}");
    assert!(message(&e).contains("\"1\"") && message(&e).contains("z = 0"), "{}", message(&e));
    // A camera under the table top, or on it.
    for z in [-0.5, 0.0] {
        let e = validate_with(|s| s.camera.pose.t[2] = z).unwrap_err();
        assert!(matches!(e, SceneError::CameraBelowTable { .. }), "{e:?}");
        assert!(message(&e).contains("above the table top"));
    }
    // A camera looking away from the objects (its pose inverted).
    let e = validate_with(|s| {
        // Turned half way round its own y axis: looking up and away.
        let turn = nalgebra::UnitQuaternion::from_axis_angle(&nalgebra::Vector3::y_axis(), std::f64::consts::PI);
        let q = s.camera.pose.rotation() * turn;
        s.camera.pose.q = [q.i, q.j, q.k, q.w];
    })
    .unwrap_err();
    assert!(matches!(e, SceneError::ObjectBehindCamera { .. }), "{e:?}");
    assert!(message(&e).contains("behind the camera"));
}

#[test]
fn ids_counts_and_stereo() {
    let e = validate_with(|s| s.objects[1].id = "1".into()).unwrap_err();
    assert!(matches!(e, SceneError::BadId { reason, .. } if reason.contains("twice")));
    let e = validate_with(|s| s.objects[1].id = "table".into()).unwrap_err();
    assert!(message(&e).contains("reserved"));
    let e = validate_with(|s| s.objects[1].id = " ".into()).unwrap_err();
    assert!(message(&e).contains("empty"));
    let e = validate_with(|s| {
        let o = s.objects[0].clone();
        s.objects = (0..MAX_OBJECTS + 1).map(|i| SceneObject { id: format!("x{i}"), ..o.clone() }).collect();
    })
    .unwrap_err();
    assert!(matches!(e, SceneError::TooManyObjects { count } if count == MAX_OBJECTS + 1));
    // A right-image keypoint needs a stereo camera.
    let mut s = generate(&SynthConfig { min_objects: 1, max_objects: 1, ..Default::default() }, 1).unwrap();
    s.camera.baseline = None;
    let e = s.validate().unwrap_err();
    assert!(matches!(e, SceneError::NoBaseline { .. }));
    assert!(message(&e).contains("camera.baseline"));
}

#[test]
fn an_object_dipping_into_the_table_is_read_as_a_false_estimate() {
    // Documented handling: accepted, and the knowledge reads the intersection with the table
    // (which cannot be false, r7) as evidence that the object is a false estimate.
    let mut s = base();
    s.objects.truncate(3);
    s.hidden_objects.clear();
    s.objects[2].pose.t[2] -= 0.03;
    let mut c = TabletopChain::new(s, ChainConfig::default(), 1).unwrap();
    c.step(5);
    let a = c.best_analysis().unwrap();
    assert!(a.evidence.intersect(2, 3));
    assert_eq!(a.objects[2].false_estimate, Decision::True);
    assert!((a.objects[2].probabilities.false_estimate - 270.0 / 312.0).abs() < 1e-9);
    assert_eq!(a.objects[0].false_estimate, Decision::False);
}

#[test]
fn odd_but_valid_scenes_are_analysed() {
    let mut s = base();
    s.hidden_objects.clear();
    // Two copies of the same box (each contains the other), a box far off the table, a box
    // larger than the table, and one without keypoints or truth.
    let mut twin = s.objects[0].clone();
    twin.id = "twin".into();
    let mut far = s.objects[1].clone();
    far.id = "far".into();
    far.pose = Pose::at([3.0, 2.0, 0.5]);
    let mut huge = s.objects[2].clone();
    huge.id = "huge".into();
    huge.size = [3.0, 3.0, 0.2];
    huge.pose = Pose::at([0.0, 0.0, 1.0]);
    s.objects.extend([twin, far, huge]);
    let mut c = TabletopChain::new(s, ChainConfig::default(), 4).unwrap();
    c.step(5);
    let a = c.best_analysis().unwrap();
    assert!(a.evidence.intersect(0, 6), "twins intersect");
    assert!(a.evidence.hover(7), "the far box touches nothing");
    let poses: Vec<_> = a.objects.iter().map(|o| o.pose).collect();
    let view = draw_view(c.scene(), &poses, &marks(&a), &ViewOptions::default());
    assert!(view.width() > 0);
    assert!(draw_graph(&a.graph).width() > 0);
}

#[test]
fn corrupted_scenes_never_panic() {
    let small = SynthConfig { min_objects: 2, max_objects: 3, keypoints: 8, ..Default::default() };
    let text = generate(&small, 3).unwrap().to_json();
    let bytes = text.as_bytes();
    let mut rng = Rng::seed(99);
    let alphabet = b"0123456789-+.eE,:[]{}\" naxyz";
    let (mut parsed, mut refused) = (0, 0);
    for _ in 0..250 {
        let mut b = bytes.to_vec();
        for _ in 0..1 + rng.below(4) {
            let at = rng.below(b.len() as u32) as usize;
            match rng.below(3) {
                0 => b[at] = alphabet[rng.below(alphabet.len() as u32) as usize],
                1 => {
                    b.remove(at);
                }
                _ => b.insert(at, alphabet[rng.below(alphabet.len() as u32) as usize]),
            }
        }
        let Ok(t) = String::from_utf8(b) else { continue };
        match Scene::from_json(&t) {
            Ok(scene) => {
                parsed += 1;
                if let Ok(mut c) = TabletopChain::new(scene, ChainConfig::default(), 1) {
                    c.step(2);
                    let a = c.best_analysis().unwrap();
                    let poses: Vec<_> = a.objects.iter().map(|o| o.pose).collect();
                    draw_view(c.scene(), &poses, &marks(&a), &ViewOptions { max_width: 200, ..Default::default() });
                    draw_graph(&a.graph);
                }
            }
            Err(e) => {
                refused += 1;
                assert!(!e.to_string().is_empty());
            }
        }
    }
    assert!(parsed > 20 && refused > 20, "parsed {parsed}, refused {refused}");
}
