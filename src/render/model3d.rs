//! The 3D semantic world (dissertation Figs. 3.38, 3.41, 3.43) as glTF 2.0 binary: walls
//! extruded to a wall height with openings at the doors, a lintel over each door, and a floor
//! slab per room in its type's colour, for simulators and viewers.
//!
//! # The model
//!
//! * Units: metres, **Y up** (glTF's convention). The floor is the plane `y = 0`; the map lies
//!   in it with its image axes along **+X** (columns, right) and **+Z** (rows, down the
//!   image), origin at the map's top-left corner: map point `(x, y)` cells is `(x * r, 0, y *
//!   r)` metres at resolution `r`. Seen from above (+Y) the model reads like the map. Worlds in
//!   a turned frame are turned onto the map, as the PNG draws them.
//! * `walls`: every cell of a unit's wall ring ([`World::wall_thickness`] deep) that no door
//!   covers, from the floor to [`Model3dOptions::wall_height`]; neighbouring rings merge, and
//!   the cells are merged into as few boxes as a greedy cover gives.
//! * `lintels`: over every door cell, from [`Model3dOptions::door_height`] to the wall height
//!   (none when they are equal); `doors`: a threshold under each door cell, in the doors' cyan.
//! * One node per room of the room layer (`room 3 (corridor)`), a slab [`SLAB_M`] thick under
//!   the interiors of its units, in its type's colour ([`unit_type_rgb`], the one palette of
//!   every picture); its `extras` give the room's `id`, `type` and `area_m2`. Units in no room
//!   (or all units, for a world without a room layer) get a slab each (`unit 5 (room)`).
//!
//! ```
//! use ksmcmc::floorplan::{Door, Unit, UnitType, World};
//! use ksmcmc::render::model3d::{world_glb, Model3dOptions};
//! let mut world = World::empty(41, 20);
//! world.units = vec![
//!     Unit::new(1, 0, 0, 21, 20, UnitType::Room),
//!     Unit::new(2, 20, 0, 21, 20, UnitType::Corridor),
//! ];
//! world.doors = vec![Door { id: 1, units: [1, 2], x0: 20, y0: 8, x1: 20, y1: 11, opening: false }];
//! let glb = world_glb(&world, 0.05, &Model3dOptions::default()).unwrap();
//! assert_eq!(&glb[..4], b"glTF");
//! // A door taller than the walls is refused.
//! let tall = Model3dOptions { wall_height: 2.0, door_height: 2.5 };
//! assert!(world_glb(&world, 0.05, &tall).unwrap_err().to_string().contains("door height"));
//! ```

use super::glb::{linear, Glb, Primitive};
use super::palette::{unit_type_rgb, DOOR_RGBA};
use crate::floorplan::world::FrameGroup;
use crate::floorplan::{Frame, Rect, UnitType, World};
use serde_json::json;

/// Thickness of the floor slabs and door thresholds, metres.
pub const SLAB_M: f64 = 0.05;
/// The walls' colour (sRGB): a light gray that shades well.
pub const WALL_RGB: [u8; 3] = [214, 217, 224];
/// The highest wall or door, metres.
pub const MAX_HEIGHT_M: f64 = 100.0;

/// Heights of the 3D world, metres.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Model3dOptions {
    /// Height of the walls (default 2.5 m).
    pub wall_height: f64,
    /// Height of the door openings (default 2.0 m): a lintel fills the wall above.
    pub door_height: f64,
}

impl Default for Model3dOptions {
    fn default() -> Self {
        Model3dOptions { wall_height: 2.5, door_height: 2.0 }
    }
}

impl Model3dOptions {
    /// Checks the heights: positive, at most [`MAX_HEIGHT_M`], doors no taller than walls.
    pub fn validate(&self) -> Result<(), Model3dError> {
        let ok = |h: f64| h.is_finite() && h > 0.0 && h <= MAX_HEIGHT_M;
        if !ok(self.wall_height) {
            return Err(Model3dError::new(format!(
                "wall height {} m: give a positive number of metres, at most {MAX_HEIGHT_M}",
                self.wall_height
            )));
        }
        if !ok(self.door_height) || self.door_height > self.wall_height {
            return Err(Model3dError::new(format!(
                "door height {} m: give a positive number of metres, at most the wall height ({} m)",
                self.door_height, self.wall_height
            )));
        }
        Ok(())
    }
}

/// Why no 3D world was made.
#[derive(Debug, Clone, PartialEq)]
pub struct Model3dError {
    message: String,
}

impl Model3dError {
    /// The error with `message`, which says what was refused and how to put it right.
    pub(crate) fn new(message: impl Into<String>) -> Model3dError {
        Model3dError { message: message.into() }
    }
}

impl std::fmt::Display for Model3dError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Model3dError {}

/// `world` as a `.glb` file (see the module docs); `resolution` is metres per map cell.
pub fn world_glb(world: &World, resolution: f64, options: &Model3dOptions) -> Result<Vec<u8>, Model3dError> {
    options.validate()?;
    if !(resolution.is_finite() && resolution > 0.0) {
        return Err(Model3dError::new(format!("resolution {resolution}: give a positive number of metres per cell")));
    }
    world.validate().map_err(|e| Model3dError::new(e.to_string()))?;
    let groups = world.frame_groups();
    let places: Vec<Place> = groups.iter().map(|g| Place { frame: g.frame, r: resolution }).collect();
    let mut glb = Glb::new();
    // Walls, lintels and doors frame by frame: the rings of units at one angle merge.
    let (mut walls, mut lintels, mut doors) = (Vec::new(), Vec::new(), Vec::new());
    for (k, g) in groups.iter().enumerate() {
        let (cells, door_rects) = wall_cells(world, g);
        walls.push((k, cells.rects(1)));
        lintels.push((k, cells.rects(2)));
        doors.push((k, door_rects));
    }
    let (h, d) = (options.wall_height, options.door_height);
    let heights = json!({ "wall_height_m": h, "door_height_m": d });
    let add = |glb: &mut Glb, name: &str, parts: &[(usize, Vec<Rect>)], (y0, y1), paint, extras| {
        let parts: Vec<&(usize, Vec<Rect>)> =
            parts.iter().filter(|(_, rects)| rects.iter().any(|r| r.w > 0 && r.h > 0)).collect();
        if !parts.is_empty() {
            let m = material(glb, paint);
            let primitives = parts.iter().map(|(k, rects)| boxes(rects, y0, y1, &places[*k], m)).collect();
            glb.node(name, primitives, extras);
        }
    };
    add(&mut glb, "walls", &walls, (0.0, h), Paint::Wall, Some(heights));
    if d < h {
        add(&mut glb, "lintels", &lintels, (d, h), Paint::Wall, None);
    }
    add(&mut glb, "doors", &doors, (-SLAB_M, 0.0), Paint::Door, None);
    for f in floors(world, &groups) {
        add(&mut glb, &f.name, &f.parts, (-SLAB_M, 0.0), Paint::Floor(f.kind), Some(f.extras));
    }
    Ok(glb.to_bytes())
}

/// What a material paints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Paint {
    Wall,
    Door,
    Floor(UnitType),
}

/// The material for `paint`, made on first use (an unused material is noise to validators).
fn material(glb: &mut Glb, paint: Paint) -> usize {
    let (name, rgb) = match paint {
        Paint::Wall => ("wall".to_string(), WALL_RGB),
        Paint::Door => ("door".to_string(), [DOOR_RGBA[0], DOOR_RGBA[1], DOOR_RGBA[2]]),
        Paint::Floor(k) => (format!("floor: {}", k.name()), unit_type_rgb(k)),
    };
    glb.material_named(&name, [linear(rgb[0]), linear(rgb[1]), linear(rgb[2]), 1.0])
}

/// A floor slab: a node's name, its rectangles (with the index of the frame group they lie
/// in), its type and the node's extras.
struct Slab {
    name: String,
    parts: Vec<(usize, Vec<Rect>)>,
    kind: UnitType,
    extras: serde_json::Value,
}

/// The floor slabs: one per room (its units' interiors, frame by frame), then one per unit in
/// no room.
fn floors(world: &World, groups: &[FrameGroup]) -> Vec<Slab> {
    let t = world.wall_thickness;
    let group_of = FrameGroup::of_units(groups, world.units.len());
    let mut out = Vec::new();
    let mut roomed = std::collections::HashSet::new();
    for room in &world.rooms {
        let units: Vec<usize> = room.units.iter().filter_map(|&id| world.unit_index(id)).collect();
        roomed.extend(room.units.iter().copied());
        let parts = (0..groups.len())
            .filter_map(|k| {
                let rects: Vec<Rect> = units
                    .iter()
                    .filter(|&&i| group_of[i] == k)
                    .filter_map(|&i| world.units[i].rect().interior(t))
                    .collect();
                (!rects.is_empty()).then(|| (k, CellGrid::union(&rects).rects(1)))
            })
            .collect();
        let extras = json!({ "id": room.id, "type": room.kind.name(), "area_m2": room.area_m2 });
        let name = format!("room {} ({})", room.id, room.kind.name());
        out.push(Slab { name, parts, kind: room.kind, extras });
    }
    for (i, u) in world.units.iter().enumerate().filter(|(_, u)| !roomed.contains(&u.id)) {
        if let Some(r) = u.rect().interior(t).filter(|_| group_of[i] != usize::MAX) {
            let extras = json!({ "unit": u.id, "type": u.kind.name() });
            let name = format!("unit {} ({})", u.id, u.kind.name());
            out.push(Slab { name, parts: vec![(group_of[i], vec![r])], kind: u.kind, extras });
        }
    }
    out
}

/// The walls (1: wall cells, 2: door cells in or between them) of the units of frame group
/// `g`, over their bounding box in its frame, and its doors' rectangles.
fn wall_cells(world: &World, g: &FrameGroup) -> (CellGrid, Vec<Rect>) {
    let t = world.wall_thickness;
    let doors: Vec<Rect> = g.doors.iter().map(|&i| world.doors[i].rect()).collect();
    let units = || g.units.iter().map(|&i| world.units[i].rect());
    let all: Vec<Rect> = units().chain(doors.iter().copied()).collect();
    let mut grid = CellGrid::over(&all);
    for r in units() {
        let ring = [
            Rect::new(r.x, r.y, r.w, t.min(r.h)),
            Rect::new(r.x, r.bottom() - t.min(r.h), r.w, t.min(r.h)),
            Rect::new(r.x, r.y, t.min(r.w), r.h),
            Rect::new(r.right() - t.min(r.w), r.y, t.min(r.w), r.h),
        ];
        for q in ring {
            grid.fill(q, 1);
        }
    }
    for &d in &doors {
        grid.fill(d, 2);
    }
    for d in world.doors.iter().filter(|d| world.door_frame(d) != g.frame) {
        if world.unit(d.units[1]).is_some_and(|u| world.unit_frame(u) == g.frame) {
            grid.open_where(d.rect(), &world.door_frame(d), &g.frame);
        }
    }
    (grid, doors)
}

/// A grid of cell values over a rectangle of the world frame.
struct CellGrid {
    area: Rect,
    cells: Vec<u8>,
}

impl CellGrid {
    /// An empty grid over the bounding box of `rects`.
    fn over(rects: &[Rect]) -> CellGrid {
        let x0 = rects.iter().map(|r| r.x).min().unwrap_or(0);
        let y0 = rects.iter().map(|r| r.y).min().unwrap_or(0);
        let x1 = rects.iter().map(|r| r.right()).max().unwrap_or(0);
        let y1 = rects.iter().map(|r| r.bottom()).max().unwrap_or(0);
        let area = Rect::new(x0, y0, (x1 - x0).max(0), (y1 - y0).max(0));
        CellGrid { area, cells: vec![0; area.w as usize * area.h as usize] }
    }

    /// The cells of `rects` set to 1.
    fn union(rects: &[Rect]) -> CellGrid {
        let mut g = CellGrid::over(rects);
        for &r in rects {
            g.fill(r, 1);
        }
        g
    }

    fn fill(&mut self, r: Rect, v: u8) {
        let Some(r) = r.intersection(&self.area) else { return };
        for y in r.y..r.bottom() {
            let row = (y - self.area.y) as usize * self.area.w as usize;
            for x in r.x..r.right() {
                self.cells[row + (x - self.area.x) as usize] = v;
            }
        }
    }

    /// Wall cells (1) whose centres lie in `door`, a rectangle of another frame `from` (a door
    /// between two wings, [`crate::floorplan::wing_doors`]), become doorway (2): the second
    /// unit's wall opens where the door crosses it.
    fn open_where(&mut self, door: Rect, from: &Frame, to: &Frame) {
        let (rf, rt) = (from.rotation(), to.rotation());
        let corners =
            [(door.x, door.y), (door.right(), door.y), (door.x, door.bottom()), (door.right(), door.bottom())].map(
                |(x, y)| {
                    let (mx, my) = rf.to_map(x as f64, y as f64);
                    rt.to_world(mx, my)
                },
            );
        let lo = |f: fn(&(f64, f64)) -> f64| libm::floor(corners.iter().map(f).fold(f64::INFINITY, f64::min)) as i32;
        let hi = |f: fn(&(f64, f64)) -> f64| libm::ceil(corners.iter().map(f).fold(f64::NEG_INFINITY, f64::max)) as i32;
        let bbox = Rect::new(lo(|c| c.0), lo(|c| c.1), hi(|c| c.0) - lo(|c| c.0), hi(|c| c.1) - lo(|c| c.1));
        let Some(r) = bbox.intersection(&self.area) else { return };
        for y in r.y..r.bottom() {
            for x in r.x..r.right() {
                let (mx, my) = rt.to_map(x as f64 + 0.5, y as f64 + 0.5);
                let (dx, dy) = rf.to_world(mx, my);
                let within =
                    dx >= door.x as f64 && dx < door.right() as f64 && dy >= door.y as f64 && dy < door.bottom() as f64;
                let i = (y - self.area.y) as usize * self.area.w as usize + (x - self.area.x) as usize;
                if within && self.cells[i] == 1 {
                    self.cells[i] = 2;
                }
            }
        }
    }

    /// The cells of value `v` as rectangles: runs along rows, each grown down while the rows
    /// below hold the same run.
    fn rects(&self, v: u8) -> Vec<Rect> {
        let (w, h) = (self.area.w as usize, self.area.h as usize);
        let mut used = vec![false; w * h];
        let free = |i: usize, used: &[bool]| self.cells[i] == v && !used[i];
        let mut out = Vec::new();
        for y in 0..h {
            let mut x = 0;
            while x < w {
                if !free(y * w + x, &used) {
                    x += 1;
                    continue;
                }
                let mut x1 = x;
                while x1 < w && free(y * w + x1, &used) {
                    x1 += 1;
                }
                let mut y1 = y + 1;
                while y1 < h && (x..x1).all(|k| free(y1 * w + k, &used)) {
                    y1 += 1;
                }
                for yy in y..y1 {
                    used[yy * w + x..yy * w + x1].fill(true);
                }
                let (ax, ay) = (self.area.x, self.area.y);
                out.push(Rect::new(ax + x as i32, ay + y as i32, (x1 - x) as i32, (y1 - y) as i32));
                x = x1;
            }
        }
        out
    }
}

/// Where world-frame points go: onto the map, then to metres.
struct Place {
    frame: Frame,
    r: f64,
}

impl Place {
    /// World-frame point `(x, y)` (cells) at height `h` (metres) as a model point.
    fn at(&self, x: f64, y: f64, h: f64) -> [f64; 3] {
        let (mx, my) = self.frame.to_map(x, y);
        [mx * self.r, h, my * self.r]
    }
}

/// Boxes over world-frame rectangles from height `y0` to `y1`, as one primitive.
fn boxes(rects: &[Rect], y0: f64, y1: f64, place: &Place, material: usize) -> Primitive {
    let mut p = Primitive { positions: Vec::new(), normals: Vec::new(), indices: Vec::new(), material };
    for r in rects.iter().filter(|r| r.w > 0 && r.h > 0) {
        let (x0, z0, x1, z1) = (r.x as f64, r.y as f64, r.right() as f64, r.bottom() as f64);
        let corners = [(x0, z0), (x1, z0), (x1, z1), (x0, z1)];
        let low = corners.map(|(x, z)| place.at(x, z, y0));
        let high = corners.map(|(x, z)| place.at(x, z, y1));
        let centre = place.at((x0 + x1) / 2.0, (z0 + z1) / 2.0, (y0 + y1) / 2.0);
        face(&mut p, high, centre);
        face(&mut p, low, centre);
        for k in 0..4 {
            let j = (k + 1) % 4;
            face(&mut p, [low[k], low[j], high[j], high[k]], centre);
        }
    }
    p
}

/// A quad (a planar convex quadrilateral, corners in order) facing away from `inside`.
fn face(p: &mut Primitive, mut q: [[f64; 3]; 4], inside: [f64; 3]) {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross =
        |a: [f64; 3], b: [f64; 3]| [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let mut n = cross(sub(q[1], q[0]), sub(q[2], q[0]));
    let centre = [0, 1, 2].map(|k| q.iter().map(|v| v[k]).sum::<f64>() / 4.0);
    if dot(n, sub(centre, inside)) < 0.0 {
        q.reverse();
        n = n.map(|c| -c);
    }
    let len = libm::sqrt(dot(n, n));
    if !len.is_finite() || len <= 0.0 {
        return;
    }
    let n = n.map(|c| (c / len) as f32);
    let base = p.positions.len() as u32;
    for v in q {
        p.positions.push(v.map(|c| c as f32));
        p.normals.push(n);
    }
    p.indices.extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::{wing_doors::join_wings, DoorLimits, Unit, UnitType};
    use crate::grid::{Cell, Grid};

    /// A door between two wings opens the walls of both units: the first unit's in its own
    /// frame, the second's in the other frame where the door crosses it.
    #[test]
    fn a_door_between_wings_opens_both_walls() {
        let mut world = World::empty(100, 60);
        world.wall_thickness = 2;
        world.units = vec![Unit::new(1, 0, 0, 50, 60, UnitType::Room), Unit::new(2, 50, 0, 50, 60, UnitType::Room)];
        world.units[1].angle = Some(1e-6);
        assert_eq!(join_wings(&mut world, &Grid::new(100, 60, Cell::Free), &DoorLimits::default()), 1);
        let groups = world.frame_groups();
        assert_eq!(groups.len(), 2);
        let opened = |k: usize| {
            let (grid, _) = wall_cells(&world, &groups[k]);
            let u = &world.units[k];
            // Doorway cells on the unit's own ring, between its corners.
            let ring = |x: i32| x < u.x + 2 || x >= u.x + u.w - 2;
            let a = grid.area;
            (0..grid.cells.len())
                .filter(|&i| grid.cells[i] == 2)
                .filter(|&i| ring(a.x + (i % a.w as usize) as i32))
                .count()
        };
        assert!(opened(0) >= 2 * 50, "the first unit's right wall opens: {}", opened(0));
        assert!(opened(1) >= 2 * 50, "the second unit's left wall opens: {}", opened(1));
    }
}
