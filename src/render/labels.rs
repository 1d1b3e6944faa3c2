//! Placing room and unit labels so that they can be read: inside their room, never on top of
//! each other, shortened or left out when they do not fit.
//!
//! A crowded map (the Cartesium building has dozens of offices along a corridor) drawn at one
//! pixel per cell leaves rooms a few dozen pixels wide, smaller than a tag such as
//! "corridor 12". Drawing every tag at its room's centre then hides the plan under a pile of
//! overlapping boxes, which is what issue 12 asked to fix. The placer here is greedy and
//! deterministic, so the page and the CLI print the same labels:
//!
//! 1. candidates are taken largest room first (ties by order given), so the rooms a reader
//!    looks at first keep their full label;
//! 2. each candidate tries its texts from longest to shortest ("corridor 12", "corr 12", "12");
//! 3. a text is placed, centred on the candidate's anchor, if its box lies inside the
//!    candidate's rectangle (rotated with the world's frame) and inside the picture, and
//!    overlaps neither an already placed label nor a blocked area (the legend);
//! 4. a candidate none of whose texts fits is left out.

use super::font;
use crate::floorplan::{UnitType, World};

/// A placed label: its text and its box (outline included) in pixels.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LabelBox {
    /// The text drawn (possibly shortened).
    pub text: String,
    /// Left edge, pixels.
    pub left: i64,
    /// Top edge, pixels.
    pub top: i64,
    /// Width, pixels.
    pub width: i64,
    /// Height, pixels.
    pub height: i64,
}

impl LabelBox {
    /// Whether two boxes share at least one pixel.
    pub fn intersects(&self, other: &LabelBox) -> bool {
        self.left < other.left + other.width
            && other.left < self.left + self.width
            && self.top < other.top + other.height
            && other.top < self.top + self.height
    }
}

/// A label to place: where, within what, and which texts to try.
#[derive(Debug, Clone, PartialEq)]
pub struct LabelCandidate {
    /// The texts to try, longest (preferred) first.
    pub texts: Vec<String>,
    /// The centre of the label and of its rectangle, pixels.
    pub centre: (f64, f64),
    /// Half the rectangle's width and height in pixels, before rotation.
    pub half: (f64, f64),
    /// The rectangle's rotation on the picture, radians (the world frame's angle).
    pub angle: f64,
    /// Larger is placed first (the room's area).
    pub priority: u64,
}

/// The size of a tag's box (text, padding and outline) for `text` at `factor`, as
/// [`super::draw_tag`] draws it.
pub fn tag_size(text: &str, factor: u32) -> (i64, i64) {
    let (w, h) = font::text_size(text, factor);
    let pad = 2 * factor as i64;
    (w as i64 + pad, h as i64 + pad)
}

/// The texts for a label of type `kind` and id `id`, longest first: "corridor 12", "corr 12",
/// "12".
pub fn label_texts(kind: UnitType, id: u32) -> Vec<String> {
    let short = match kind {
        UnitType::Corridor => Some("corr"),
        UnitType::Other => Some("oth"),
        UnitType::Unknown => Some("unk"),
        UnitType::Room | UnitType::Hall => None,
    };
    let mut texts = vec![format!("{} {id}", kind.name())];
    if let Some(s) = short {
        texts.push(format!("{s} {id}"));
    }
    texts.push(id.to_string());
    texts
}

/// Places labels on a `width` x `height` picture with text at `factor` pixels per font pixel,
/// avoiding the `blocked` boxes; returns the boxes placed, in placement order (largest
/// candidate first). No two returned boxes intersect, and none intersects a blocked box.
///
/// ```
/// use ksmcmc::render::{place_labels, LabelCandidate};
///
/// let room = |x: f64, w: f64, texts: &[&str]| LabelCandidate {
///     texts: texts.iter().map(|t| t.to_string()).collect(),
///     centre: (x, 20.0),
///     half: (w / 2.0, 20.0),
///     angle: 0.0,
///     priority: 1,
/// };
/// // A 40-pixel corridor beside an 80-pixel room: "corridor 12" and "corr 12" are too wide
/// // for the corridor, "12" fits; "room 3" fits the room.
/// let corridor = room(20.0, 40.0, &["corridor 12", "corr 12", "12"]);
/// let placed = place_labels(&[corridor, room(80.0, 80.0, &["room 3", "3"])], 120, 40, 2, &[]);
/// assert_eq!(placed.iter().map(|b| b.text.as_str()).collect::<Vec<_>>(), ["12", "room 3"]);
/// assert!(!placed[0].intersects(&placed[1]));
/// ```
pub fn place_labels(
    candidates: &[LabelCandidate],
    width: u32,
    height: u32,
    factor: u32,
    blocked: &[LabelBox],
) -> Vec<LabelBox> {
    let mut order: Vec<usize> = (0..candidates.len()).collect();
    crate::sort::sort_by(&mut order, |&a, &b| candidates[b].priority.cmp(&candidates[a].priority).then(a.cmp(&b)));
    let mut placed: Vec<LabelBox> = Vec::new();
    for i in order {
        let c = &candidates[i];
        if !(c.centre.0.is_finite() && c.centre.1.is_finite() && c.angle.is_finite()) {
            continue;
        }
        let (sin, cos) = (c.angle.sin().abs(), c.angle.cos().abs());
        let fitting = c.texts.iter().find_map(|text| {
            let (w, h) = tag_size(text, factor);
            let (a, b) = (w as f64 / 2.0, h as f64 / 2.0);
            // A centred axis-aligned box fits in the rotated rectangle iff its corners do.
            if a * cos + b * sin > c.half.0 + 1e-9 || a * sin + b * cos > c.half.1 + 1e-9 {
                return None;
            }
            let left = (c.centre.0 - a).round();
            let top = (c.centre.1 - b).round();
            if left < 0.0 || top < 0.0 || left + w as f64 > width as f64 || top + h as f64 > height as f64 {
                return None;
            }
            let candidate = LabelBox { text: text.clone(), left: left as i64, top: top as i64, width: w, height: h };
            let free = placed.iter().chain(blocked).all(|p| !p.intersects(&candidate));
            free.then_some(candidate)
        });
        placed.extend(fitting);
    }
    placed
}

/// The label candidates of `world` on a map drawn at `scale` pixels per cell: one per room at
/// its largest unit when the world has a room layer, else one per unit.
pub fn world_label_candidates(world: &World, scale: u32) -> Vec<LabelCandidate> {
    let s = scale as f64;
    let candidate = |unit: &crate::floorplan::Unit, kind: UnitType, id: u32, priority: u64| {
        // Each unit in its own frame (issue 13): the world frame unless it has an angle.
        let frame = world.unit_frame(unit);
        let (cx, cy) = unit.rect().center();
        let (mx, my) = if frame.is_identity() { (cx, cy) } else { frame.to_map(cx, cy) };
        LabelCandidate {
            texts: label_texts(kind, id),
            centre: (mx * s, my * s),
            half: (unit.w as f64 * s / 2.0, unit.h as f64 * s / 2.0),
            angle: frame.angle,
            priority,
        }
    };
    let drawable = |u: &&crate::floorplan::Unit| u.w >= 1 && u.h >= 1;
    if world.rooms.is_empty() {
        return world.units.iter().filter(drawable).map(|u| candidate(u, u.kind, u.id, area(u))).collect();
    }
    world
        .rooms
        .iter()
        .filter_map(|room| {
            let units = room.units.iter().filter_map(|&id| world.unit(id)).filter(drawable);
            let largest = units.clone().max_by_key(|u| area(u))?;
            Some(candidate(largest, room.kind, room.id, units.map(area).sum()))
        })
        .collect()
}

fn area(u: &crate::floorplan::Unit) -> u64 {
    u.w.max(0) as u64 * u.h.max(0) as u64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn candidate(x: f64, y: f64, w: f64, h: f64, kind: UnitType, id: u32) -> LabelCandidate {
        LabelCandidate {
            texts: label_texts(kind, id),
            centre: (x, y),
            half: (w / 2.0, h / 2.0),
            angle: 0.0,
            priority: (w * h) as u64,
        }
    }

    fn assert_disjoint(boxes: &[LabelBox]) {
        for (i, a) in boxes.iter().enumerate() {
            for b in &boxes[i + 1..] {
                assert!(!a.intersects(b), "{a:?} overlaps {b:?}");
            }
        }
    }

    #[test]
    fn texts_shorten_in_order() {
        assert_eq!(label_texts(UnitType::Corridor, 12), ["corridor 12", "corr 12", "12"]);
        assert_eq!(label_texts(UnitType::Room, 3), ["room 3", "3"]);
    }

    #[test]
    fn crowded_offices_along_a_corridor_get_disjoint_labels() {
        // A Cartesium-like row: a long corridor with twenty narrow offices above and below,
        // at one pixel per cell, plus a few overlapping units.
        let mut cands = vec![candidate(300.0, 60.0, 600.0, 24.0, UnitType::Corridor, 1)];
        for i in 0..20 {
            let x = 15.0 + i as f64 * 30.0;
            cands.push(candidate(x, 30.0, 30.0, 44.0, UnitType::Room, 2 + i));
            cands.push(candidate(x, 90.0, 30.0, 44.0, UnitType::Room, 40 + i));
            cands.push(candidate(x + 7.0, 36.0, 24.0, 30.0, UnitType::Other, 80 + i));
        }
        let placed = place_labels(&cands, 600, 120, 2, &[]);
        assert_disjoint(&placed);
        assert!(placed.iter().any(|b| b.text == "corridor 1"), "{placed:?}");
        // Every office still shows its number; the overlapping "other" units give way.
        assert!(placed.iter().filter(|b| b.text.len() <= 2).count() >= 40, "{placed:?}");
        for b in &placed {
            assert!(b.left >= 0 && b.top >= 0 && b.left + b.width <= 600 && b.top + b.height <= 120);
        }
    }

    #[test]
    fn labels_that_do_not_fit_are_hidden_and_blocked_areas_avoided() {
        let tiny = candidate(10.0, 10.0, 6.0, 6.0, UnitType::Room, 1234);
        assert!(place_labels(&[tiny], 100, 100, 2, &[]).is_empty());
        let big = candidate(50.0, 50.0, 100.0, 100.0, UnitType::Hall, 5);
        let legend = LabelBox { text: String::new(), left: 0, top: 0, width: 100, height: 100 };
        assert!(place_labels(std::slice::from_ref(&big), 100, 100, 2, &[legend]).is_empty());
        assert_eq!(place_labels(&[big], 100, 100, 2, &[])[0].text, "hall 5");
        // A rotated narrow rectangle does not take a wide label.
        let mut rotated = candidate(50.0, 50.0, 90.0, 20.0, UnitType::Room, 7);
        assert_eq!(place_labels(std::slice::from_ref(&rotated), 100, 100, 2, &[])[0].text, "room 7");
        rotated.angle = std::f64::consts::FRAC_PI_2;
        assert_eq!(place_labels(&[rotated], 100, 100, 2, &[])[0].text, "7");
    }
}
