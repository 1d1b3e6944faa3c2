//! Room shapes: each room of a world as polygons on the map, and each door as a line across
//! its doorway. The vector exports (`world.geojson`, [`super::geojson`], and `world.svg`,
//! [`crate::render::svg`]) draw these, so that both show the same plan.
//!
//! # A room's polygon
//!
//! A room is the union of its units' *floors*: each unit's rectangle inset by half its wall
//! depth, i.e. bounded by the centre lines of its walls. Two units sharing a wall then meet
//! exactly on its centre line, so that neighbouring rooms share edges instead of overlapping,
//! and the units of one room cut apart by a seam merge into one polygon. The union is exact
//! ([`outline`], in half cells of the world frame) and turned onto the map with the world's
//! [`Frame`]; a room whose floors do not touch is a multi-polygon.
//!
//! Rooms never overlap:
//!
//! * where floors of two rooms overlap (overlapping units), the room listed first in
//!   `world.rooms` keeps the overlap;
//! * a room without units (free space the chain left unexplained, or a part of a unit that
//!   the room layer split off at a doorway) is outlined from its cells in the label image,
//!   taken in the world frame (world cells whose centre lies on one of its map cells), and
//!   those cells are cut out of the other rooms' floors;
//! * a room whose floors are all taken by rooms before it is outlined from its label cells
//!   (not cut out of others).
//!
//! A room's polygon area is therefore close to, but not the same as, its `area_m2`, the free
//! cells the label image gives it: the polygon includes half of its walls and any furniture,
//! and leaves out free cells beyond its units that the label image gave it.
//!
//! # A door's line
//!
//! A door is a rectangle of cells through the wall(s) between two units; its line runs along
//! the rectangle's long side through the middle of the wall, from edge to edge of the opening.
//! A square door (as wide as the wall is deep) runs along the wall the two units share: across
//! the line between their centres.

use super::outline::{self, Polygon};
use crate::floorplan::rooms::map_cell;
use crate::floorplan::world::{Door, Frame, FrameGroup, Room, UnitType, World, WorldError};
use crate::grid::Grid;

/// A point on the map in cells: `x` right, `y` down, `(0, 0)` the top-left corner of the map's
/// top-left cell.
pub type MapPoint = (f64, f64);

/// A polygon on the map: its exterior and holes, each ring listed once around (not closed).
/// Exteriors run counter-clockwise on the screen (y down), holes clockwise.
#[derive(Debug, Clone, PartialEq)]
pub struct MapPolygon {
    /// The outer ring.
    pub exterior: Vec<MapPoint>,
    /// The holes.
    pub holes: Vec<Vec<MapPoint>>,
}

/// Where a room's shape came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShapeSource {
    /// The union of its units' floors.
    Units,
    /// Its cells in the label image.
    Labels,
}

/// One room's shape.
#[derive(Debug, Clone, PartialEq)]
pub struct RoomShape {
    /// The room's id (its value in the label image).
    pub id: u32,
    /// The room's type.
    pub kind: UnitType,
    /// The room's name, if a person gave it one (`rooms[].name`).
    pub name: Option<String>,
    /// Its free floor area (`area_m2` of `world.json`), square metres.
    pub area_m2: f64,
    /// Its polygons (none if the room has neither floor nor label cells).
    pub polygons: Vec<MapPolygon>,
    /// A point inside the room for its label: the middle of its largest floor, or of its
    /// deepest cell.
    pub anchor: MapPoint,
    /// The width and height (cells, along the world frame's axes) of free room around the
    /// anchor: how large a label may be.
    pub label_room: (f64, f64),
    /// Where the shape came from.
    pub source: ShapeSource,
    /// The angle (radians, as the frame's) of the frame the shape was drawn in, whose axes
    /// `label_room` runs along: the world frame's, or in a world of units at several angles
    /// the frame most of the room's units lie in.
    pub angle: f64,
}

/// One door's line across its doorway.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoorLine {
    /// The door's id.
    pub id: u32,
    /// The two ends of the line.
    pub ends: [MapPoint; 2],
}

/// The shapes of a world's rooms and doors on its map.
#[derive(Debug, Clone, PartialEq)]
pub struct FloorShapes {
    /// One per room, in the order of `world.rooms`.
    pub rooms: Vec<RoomShape>,
    /// One per door, in the order of `world.doors`.
    pub doors: Vec<DoorLine>,
    /// The map's width and height in cells.
    pub map_size: [u32; 2],
    /// The world frame's angle on the map, radians.
    pub angle: f64,
}

/// Why shapes could not be made.
#[derive(Debug, Clone, PartialEq)]
pub enum ShapeError {
    /// The world is not valid ([`World::validate`]).
    World(WorldError),
    /// The label image is not the map's size.
    Labels {
        /// The label image's width and height.
        labels: [usize; 2],
        /// The map's (`frame.map_size`).
        map: [u32; 2],
    },
}

impl std::fmt::Display for ShapeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ShapeError::World(e) => write!(f, "{e}"),
            ShapeError::Labels { labels, map } => write!(
                f,
                "the room labels are {}x{} cells but the world's map is {}x{} (frame.map_size): \
                 pass the labels made with this world (labels.pgm of the same run)",
                labels[0], labels[1], map[0], map[1]
            ),
        }
    }
}

impl std::error::Error for ShapeError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ShapeError::World(e) => Some(e),
            ShapeError::Labels { .. } => None,
        }
    }
}

/// The shapes of `world`'s rooms and doors, with `labels` the room id of every map cell
/// (`labels.pgm`, as [`crate::floorplan::rooms::RoomLayer::explain`] returns it).
///
/// ```
/// use ksmcmc::floorplan::shapes::floor_shapes;
/// use ksmcmc::floorplan::{Room, Unit, UnitType, World};
/// use ksmcmc::grid::Grid;
///
/// // Two units sharing the wall column 10 (walls 1 cell deep), one room each.
/// let mut world = World::empty(21, 8);
/// for (id, x) in [(1, 0), (2, 10)] {
///     world.units.push(Unit::new(id, x, 0, 11, 8, UnitType::Room));
///     world.rooms.push(Room { id, kind: UnitType::Room, units: vec![id], area_m2: 1.0, doors: vec![], opens_to: vec![], name: None });
/// }
/// let shapes = floor_shapes(&world, &Grid::new(21, 8, 0)).unwrap();
/// // Floors end on the shared wall's centre line, x = 10.5.
/// assert_eq!(shapes.rooms[0].polygons[0].exterior, vec![(0.5, 0.5), (0.5, 7.5), (10.5, 7.5), (10.5, 0.5)]);
/// assert_eq!(shapes.rooms[1].polygons[0].exterior[0], (10.5, 0.5));
/// ```
pub fn floor_shapes(world: &World, labels: &Grid<u16>) -> Result<FloorShapes, ShapeError> {
    world.validate().map_err(ShapeError::World)?;
    let map = world.frame.map_size;
    if [labels.width(), labels.height()] != [map[0] as usize, map[1] as usize] {
        return Err(ShapeError::Labels { labels: [labels.width(), labels.height()], map });
    }
    let groups = world.frame_groups();
    let rooms = if groups.len() > 1 {
        rooms_by_frame(world, labels, &groups)
    } else {
        let plan = Plan::new(world, labels);
        world.rooms.iter().enumerate().map(|(k, r)| plan.room(k, r)).collect()
    };
    let doors = world.doors.iter().map(|d| door_line(world, d)).collect();
    Ok(FloorShapes { rooms, doors, map_size: map, angle: world.frame.angle })
}

/// The room shapes of a world of units at several angles (issue 13): each room outlined from
/// its label cells, taken in the frame most of its units lie in (the world frame for a room
/// with none), so that its walls along that frame's axes are straight lines. The floors of
/// units of several angles do not union into exact polygons, and a wing's units need not
/// tile the rooms the room layer found, so the labels give the shape. Rooms drawn in one
/// frame never overlap; two drawn in different frames may overlap, or leave a sliver between
/// them, less than a cell wide where their label cells meet.
fn rooms_by_frame(world: &World, labels: &Grid<u16>, groups: &[FrameGroup]) -> Vec<RoomShape> {
    let group_of = FrameGroup::of_units(groups, world.units.len());
    let frame_of = |room: &Room| {
        let count =
            |k: usize| room.units.iter().filter(|&&id| world.unit_index(id).is_some_and(|i| group_of[i] == k)).count();
        (0..groups.len()).max_by_key(|&k| (count(k), std::cmp::Reverse(k))).unwrap_or(0)
    };
    let room_frame: Vec<usize> = world.rooms.iter().map(frame_of).collect();
    let mut shapes: Vec<Option<RoomShape>> = vec![None; world.rooms.len()];
    for (k, g) in groups.iter().enumerate() {
        let here: Vec<usize> = (0..world.rooms.len()).filter(|&i| room_frame[i] == k).collect();
        if here.is_empty() {
            continue;
        }
        // The frame's plan of these rooms, without units: each outlined from its labels.
        let mut sub = World::empty(world.frame.map_size[0], world.frame.map_size[1]);
        sub.frame = g.frame;
        sub.rooms = here.iter().map(|&i| Room { units: Vec::new(), ..world.rooms[i].clone() }).collect();
        let plan = Plan::new(&sub, labels);
        for (j, &i) in here.iter().enumerate() {
            shapes[i] = Some(plan.room(j, &sub.rooms[j]));
        }
    }
    shapes.into_iter().flatten().collect()
}

/// A rectangle `[x0, y0, x1, y1]` in half cells of the world frame.
type Half = [i64; 4];

/// What every room's shape needs: the floors, the rooms outlined from labels and where their
/// cells are.
struct Plan<'a> {
    world: &'a World,
    labels: &'a Grid<u16>,
    /// Each unit's floor and the index of the room it belongs to (units of no room left out).
    floors: Vec<(Half, usize)>,
    /// By label value: whether that room is outlined from its labels and cut out of floors.
    cut: Vec<bool>,
    /// The rooms cut out of floors, with the world-frame box (half cells) around their cells.
    cut_boxes: Vec<(u32, Half)>,
    /// By label value: the world-frame box (half cells) around the room's label cells.
    boxes: Vec<Option<Half>>,
}

impl<'a> Plan<'a> {
    fn new(world: &'a World, labels: &'a Grid<u16>) -> Plan<'a> {
        let t = world.wall_thickness as i64;
        let mut floors = Vec::new();
        for (k, room) in world.rooms.iter().enumerate() {
            for u in room.units.iter().filter_map(|&id| world.unit(id)) {
                let (x, y, w, h) = (u.x as i64, u.y as i64, u.w as i64, u.h as i64);
                let r = [2 * x + t, 2 * y + t, 2 * (x + w) - t, 2 * (y + h) - t];
                if r[0] < r[2] && r[1] < r[3] && !floors.iter().any(|&(f, _)| f == r) {
                    floors.push((r, k));
                }
            }
        }
        let mut cut = vec![false; 1 << 16];
        for (k, room) in world.rooms.iter().enumerate() {
            if !floors.iter().any(|&(_, r)| r == k) {
                if let Ok(l) = u16::try_from(room.id) {
                    cut[l as usize] = true;
                }
            }
        }
        let boxes = label_boxes(world, labels);
        let cut_boxes = (0..cut.len()).filter(|&l| cut[l]).filter_map(|l| Some((l as u32, boxes[l]?))).collect();
        Plan { world, labels, floors, cut, cut_boxes, boxes }
    }

    /// The label at the map cell under world cell `(x, y)`, 0 off the map.
    fn label_under(&self, x: i64, y: i64) -> u16 {
        let (w, h) = (self.labels.width(), self.labels.height());
        match (i32::try_from(x), i32::try_from(y)) {
            (Ok(x), Ok(y)) => map_cell(self.world, x, y, w, h).map_or(0, |(mx, my)| *self.labels.at(mx, my)),
            _ => 0,
        }
    }

    fn room(&self, k: usize, room: &Room) -> RoomShape {
        let own: Vec<Half> = self.floors.iter().filter(|f| f.1 == k).map(|f| f.0).collect();
        self.floor_shape(k, room, &own).unwrap_or_else(|| self.label_shape(room))
    }

    /// The union of the room's floors less earlier rooms' floors and label-outlined rooms.
    fn floor_shape(&self, k: usize, room: &Room, own: &[Half]) -> Option<RoomShape> {
        let bbox =
            own.iter().copied().reduce(|a, b| [a[0].min(b[0]), a[1].min(b[1]), a[2].max(b[2]), a[3].max(b[3])])?;
        let clip = |r: &Half| -> Option<Half> {
            let c = [r[0].max(bbox[0]), r[1].max(bbox[1]), r[2].min(bbox[2]), r[3].min(bbox[3])];
            (c[0] < c[2] && c[1] < c[3]).then_some(c)
        };
        let taken: Vec<Half> = self.floors.iter().filter(|f| f.1 < k).filter_map(|f| clip(&f.0)).collect();
        let zones: Vec<Half> =
            self.cut_boxes.iter().filter(|(l, _)| *l != room.id).filter_map(|(_, b)| clip(b)).collect();
        // Grid lines: every floor edge, and every world cell edge where label cells are cut out.
        let lines = |a: usize, b: usize| {
            let rects = own.iter().chain(&taken).flat_map(move |r| [r[a], r[b]]);
            let cells = zones.iter().flat_map(move |z| (z[a]..=z[b]).filter(|v| v % 2 == 0));
            outline::edges(rects.chain(cells))
        };
        let (xs, ys) = (lines(0, 2), lines(1, 3));
        let filled = |c: Half| {
            own.iter().any(|r| outline::covers(r, &c))
                && !taken.iter().any(|r| outline::covers(r, &c))
                && !(zones.iter().any(|z| outline::covers(z, &c))
                    && self.cut[self.label_under(c[0].div_euclid(2), c[1].div_euclid(2)) as usize])
        };
        let polygons = outline::trace_grid(&xs, &ys, filled);
        if polygons.is_empty() {
            return None;
        }
        // The label goes in the middle of the largest floor if that is the room's, else in
        // its deepest piece.
        let largest = own.iter().max_by_key(|r| (r[2] - r[0]) * (r[3] - r[1])).copied().unwrap_or(bbox);
        let (cx, cy) = ((largest[0] + largest[2]) / 2, (largest[1] + largest[3]) / 2);
        let (anchor, size) = if filled([cx, cy, cx + 1, cy + 1]) {
            centre_and_size(largest)
        } else {
            centre_and_size(outline::deepest(&xs, &ys, filled)?.0)
        };
        Some(self.shape(room, polygons, anchor, size, ShapeSource::Units))
    }

    /// The room's cells in the label image, taken in the world frame.
    fn label_shape(&self, room: &Room) -> RoomShape {
        let b = u16::try_from(room.id).ok().and_then(|l| self.boxes[l as usize]);
        let Some(b) = b else {
            return self.shape(room, Vec::new(), (0.0, 0.0), (0.0, 0.0), ShapeSource::Labels);
        };
        let xs: Vec<i64> = (b[0]..=b[2]).step_by(2).collect();
        let ys: Vec<i64> = (b[1]..=b[3]).step_by(2).collect();
        let filled = |c: Half| self.label_under(c[0] / 2, c[1] / 2) as u32 == room.id;
        let polygons = outline::trace_grid(&xs, &ys, filled);
        let (anchor, size) = match outline::deepest(&xs, &ys, filled) {
            Some((c, depth)) => {
                let side = (2 * depth - 1) as f64;
                (((c[0] + c[2]) as f64 / 4.0, (c[1] + c[3]) as f64 / 4.0), (side, side))
            }
            None => ((0.0, 0.0), (0.0, 0.0)),
        };
        self.shape(room, polygons, anchor, size, ShapeSource::Labels)
    }

    /// A room's shape from polygons in half cells and an anchor in world cells.
    fn shape(
        &self,
        room: &Room,
        polygons: Vec<Polygon>,
        anchor: (f64, f64),
        label_room: (f64, f64),
        source: ShapeSource,
    ) -> RoomShape {
        let ring = |r: &Vec<(i64, i64)>| -> Vec<MapPoint> {
            r.iter().map(|&(x, y)| to_map(self.world, x as f64 / 2.0, y as f64 / 2.0)).collect()
        };
        let polygons = polygons
            .iter()
            .map(|p| MapPolygon { exterior: ring(&p.exterior), holes: p.holes.iter().map(ring).collect() })
            .collect();
        RoomShape {
            id: room.id,
            kind: room.kind,
            name: room.name.clone(),
            area_m2: room.area_m2,
            polygons,
            anchor: to_map(self.world, anchor.0, anchor.1),
            label_room,
            source,
            angle: self.world.frame.angle,
        }
    }
}

/// The centre and the size of a half-cell rectangle, in world cells.
fn centre_and_size(r: Half) -> ((f64, f64), (f64, f64)) {
    let half = |a: i64| a as f64 / 2.0;
    ((half(r[0] + r[2]) / 2.0, half(r[1] + r[3]) / 2.0), (half(r[2] - r[0]), half(r[3] - r[1])))
}

/// A world-frame point (cells) on the map.
pub fn to_map(world: &World, x: f64, y: f64) -> MapPoint {
    frame_to_map(&world.frame, x, y)
}

/// A point of `frame` (cells) on the map.
pub fn frame_to_map(frame: &Frame, x: f64, y: f64) -> MapPoint {
    if frame.is_identity() {
        (x, y)
    } else {
        frame.to_map(x, y)
    }
}

/// By label value, the world-frame box (half cells, a cell of margin, inside the world) around
/// the map cells with that label.
fn label_boxes(world: &World, labels: &Grid<u16>) -> Vec<Option<Half>> {
    let mut map_boxes: Vec<Option<[usize; 4]>> = vec![None; 1 << 16];
    for y in 0..labels.height() {
        for (x, &l) in labels.row(y).iter().enumerate() {
            if l != 0 {
                let b = map_boxes[l as usize].get_or_insert([x, y, x, y]);
                *b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
            }
        }
    }
    let [ww, wh] = world.frame.world_size.map(|v| v as i64);
    map_boxes
        .into_iter()
        .map(|b| {
            let [x0, y0, x1, y1] = b?.map(|v| v as f64);
            let corners = [(x0, y0), (x1 + 1.0, y0), (x0, y1 + 1.0), (x1 + 1.0, y1 + 1.0)].map(|(x, y)| {
                if world.frame.is_identity() {
                    (x, y)
                } else {
                    world.frame.to_world(x, y)
                }
            });
            let lo = |f: fn(&(f64, f64)) -> f64| corners.iter().map(f).fold(f64::INFINITY, f64::min);
            let hi = |f: fn(&(f64, f64)) -> f64| corners.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
            let bx0 = (libm::floor(lo(|c| c.0)) as i64 - 1).clamp(0, ww);
            let by0 = (libm::floor(lo(|c| c.1)) as i64 - 1).clamp(0, wh);
            let bx1 = (libm::ceil(hi(|c| c.0)) as i64 + 1).clamp(0, ww);
            let by1 = (libm::ceil(hi(|c| c.1)) as i64 + 1).clamp(0, wh);
            (bx0 < bx1 && by0 < by1).then_some([2 * bx0, 2 * by0, 2 * bx1, 2 * by1])
        })
        .collect()
}

/// A door's line (see the module docs), on the map.
fn door_line(world: &World, d: &Door) -> DoorLine {
    let r = d.rect();
    let (x0, y0, x1, y1) = (r.x as i64, r.y as i64, r.right() as i64, r.bottom() as i64);
    let along_x = match (r.w).cmp(&r.h) {
        std::cmp::Ordering::Greater => true,
        std::cmp::Ordering::Less => false,
        std::cmp::Ordering::Equal => match (world.unit(d.units[0]), world.unit(d.units[1])) {
            // Units side by side (apart along x) share an upright wall: the door runs along y.
            (Some(a), Some(b)) => {
                let (ca, cb) = (a.rect().center(), b.rect().center());
                (ca.0 - cb.0).abs() < (ca.1 - cb.1).abs()
            }
            _ => false,
        },
    };
    let ends = if along_x {
        let y = (y0 + y1) as f64 / 2.0;
        [(x0 as f64, y), (x1 as f64, y)]
    } else {
        let x = (x0 + x1) as f64 / 2.0;
        [(x, y0 as f64), (x, y1 as f64)]
    };
    let frame = world.door_frame(d);
    DoorLine { id: d.id, ends: ends.map(|(x, y)| frame_to_map(&frame, x, y)) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::Unit;

    fn unit(id: u32, x: i32, y: i32, w: i32, h: i32) -> Unit {
        Unit::new(id, x, y, w, h, UnitType::Room)
    }

    fn room(id: u32, units: &[u32]) -> Room {
        Room {
            id,
            kind: UnitType::Room,
            units: units.to_vec(),
            area_m2: 0.0,
            doors: vec![],
            opens_to: vec![],
            name: None,
        }
    }

    fn exteriors(s: &RoomShape) -> Vec<Vec<MapPoint>> {
        s.polygons.iter().map(|p| p.exterior.clone()).collect()
    }

    #[test]
    fn the_units_of_a_room_merge_on_their_wall_centre_lines() {
        // Walls 3 cells deep: an L of a 20x10 unit and a 10x15 unit below it sharing 3 rows of
        // wall, and a third unit, another room, right of the first.
        let mut world = World::empty(40, 30);
        world.wall_thickness = 3;
        world.units = vec![unit(1, 0, 0, 20, 10), unit(2, 0, 7, 10, 15), unit(3, 17, 0, 20, 10)];
        world.rooms = vec![room(1, &[1, 2]), room(2, &[3])];
        let s = floor_shapes(&world, &Grid::new(40, 30, 0)).unwrap();
        assert_eq!(
            exteriors(&s.rooms[0]),
            vec![vec![(1.5, 1.5), (1.5, 20.5), (8.5, 20.5), (8.5, 8.5), (18.5, 8.5), (18.5, 1.5)]]
        );
        assert_eq!(exteriors(&s.rooms[1]), vec![vec![(18.5, 1.5), (18.5, 8.5), (35.5, 8.5), (35.5, 1.5)]]);
        assert_eq!(s.rooms[0].source, ShapeSource::Units);
        // The label sits in the middle of the room's largest floor, the 17x7 one.
        assert_eq!((s.rooms[0].anchor, s.rooms[0].label_room), ((10.0, 5.0), (17.0, 7.0)));
    }

    #[test]
    fn overlapping_floors_go_to_the_room_listed_first_and_disjoint_floors_are_two_polygons() {
        let mut world = World::empty(60, 20);
        world.units = vec![unit(1, 0, 0, 21, 11), unit(2, 10, 5, 21, 11), unit(3, 40, 0, 11, 11)];
        world.rooms = vec![room(1, &[1]), room(2, &[2, 3])];
        let s = floor_shapes(&world, &Grid::new(60, 20, 0)).unwrap();
        assert_eq!(exteriors(&s.rooms[0]), vec![vec![(0.5, 0.5), (0.5, 10.5), (20.5, 10.5), (20.5, 0.5)]]);
        assert_eq!(
            exteriors(&s.rooms[1]),
            vec![
                vec![(40.5, 0.5), (40.5, 10.5), (50.5, 10.5), (50.5, 0.5)],
                vec![(20.5, 5.5), (20.5, 10.5), (10.5, 10.5), (10.5, 15.5), (30.5, 15.5), (30.5, 5.5)],
            ]
        );
    }

    #[test]
    fn a_room_without_units_is_cut_out_of_the_floor_it_lies_in() {
        // One 20x12 unit (room 1); the label image gives its cells x 12..17, y 3..7 to room 2,
        // which has no units (a doorway split), and the cells x 2..11, y 1..10 to room 1.
        let mut world = World::empty(20, 12);
        world.units = vec![unit(1, 0, 0, 20, 12)];
        world.rooms = vec![room(1, &[1]), room(2, &[])];
        let mut labels = Grid::new(20, 12, 0u16);
        for y in 1..11 {
            for x in 1..19 {
                *labels.at_mut(x, y) = if (12..17).contains(&x) && (3..7).contains(&y) { 2 } else { 1 };
            }
        }
        let s = floor_shapes(&world, &labels).unwrap();
        assert_eq!(exteriors(&s.rooms[1]), vec![vec![(12.0, 3.0), (12.0, 7.0), (17.0, 7.0), (17.0, 3.0)]]);
        assert_eq!(s.rooms[1].source, ShapeSource::Labels);
        // Its deepest cells are x 13..16, y 4..6; of those nearest their middle, the first.
        assert_eq!((s.rooms[1].anchor, s.rooms[1].label_room), ((14.5, 4.5), (3.0, 3.0)));
        let r1 = &s.rooms[0].polygons;
        assert_eq!(r1.len(), 1);
        assert_eq!(r1[0].exterior, vec![(0.5, 0.5), (0.5, 11.5), (19.5, 11.5), (19.5, 0.5)]);
        assert_eq!(r1[0].holes, vec![vec![(12.0, 3.0), (17.0, 3.0), (17.0, 7.0), (12.0, 7.0)]]);
    }

    #[test]
    fn a_rotated_frame_turns_the_polygons_onto_the_map() {
        let mut world = World::empty(50, 40);
        world.frame.angle = 0.3;
        world.frame.world_size = [60, 55];
        world.units = vec![unit(1, 10, 10, 21, 11)];
        world.rooms = vec![room(1, &[1])];
        let s = floor_shapes(&world, &Grid::new(50, 40, 0)).unwrap();
        let want: Vec<MapPoint> = [(10.5, 10.5), (10.5, 20.5), (30.5, 20.5), (30.5, 10.5)]
            .iter()
            .map(|&(x, y)| world.frame.to_map(x, y))
            .collect();
        assert_eq!(exteriors(&s.rooms[0]), vec![want]);
        assert_eq!(s.angle, 0.3);
    }

    #[test]
    fn doors_run_along_the_wall_through_its_middle() {
        let mut world = World::empty(40, 40);
        world.units = vec![unit(1, 0, 0, 11, 11), unit(2, 10, 0, 11, 11), unit(3, 0, 10, 11, 11)];
        world.doors = vec![
            Door { id: 4, units: [1, 2], x0: 10, y0: 3, x1: 10, y1: 6, opening: false },
            Door { id: 5, units: [1, 3], x0: 3, y0: 10, x1: 7, y1: 10, opening: false },
            Door { id: 6, units: [1, 2], x0: 10, y0: 8, x1: 10, y1: 8, opening: false },
            Door { id: 7, units: [1, 3], x0: 8, y0: 10, x1: 8, y1: 10, opening: false },
        ];
        let s = floor_shapes(&world, &Grid::new(40, 40, 0)).unwrap();
        let ends: Vec<[MapPoint; 2]> = s.doors.iter().map(|d| d.ends).collect();
        assert_eq!(
            ends,
            vec![
                [(10.5, 3.0), (10.5, 7.0)],
                [(3.0, 10.5), (8.0, 10.5)],
                [(10.5, 8.0), (10.5, 9.0)],
                [(8.0, 10.5), (9.0, 10.5)],
            ]
        );
    }

    #[test]
    fn a_room_with_neither_floor_nor_label_cells_has_no_polygons() {
        // Unit 1 is no wider than its walls are deep (2 cells, walls 2 deep): no floor, and no
        // cell of the label image is room 1's.
        let mut world = World::empty(20, 10);
        world.wall_thickness = 2;
        world.units = vec![unit(1, 2, 2, 2, 2)];
        world.rooms = vec![room(1, &[1])];
        let s = floor_shapes(&world, &Grid::new(20, 10, 0)).unwrap();
        assert_eq!((s.rooms.len(), s.rooms[0].polygons.len(), s.rooms[0].source), (1, 0, ShapeSource::Labels));
        let origin = crate::floorplan::georef::MapOrigin { resolution: 0.05, origin: [0.0; 3], height: 10 };
        let text = crate::floorplan::geojson::geojson(&s, &origin, None);
        assert!(text.contains(r#""feature_type":"unit","geometry":null"#), "{text}");
    }

    #[test]
    fn bad_worlds_and_labels_of_another_size_are_refused() {
        let mut world = World::empty(20, 10);
        let e = floor_shapes(&world, &Grid::new(10, 10, 0)).unwrap_err().to_string();
        assert!(e.contains("the room labels are 10x10 cells but the world's map is 20x10"), "{e}");
        world.units.push(unit(1, 15, 0, 10, 5));
        let e = floor_shapes(&world, &Grid::new(20, 10, 0)).unwrap_err();
        assert!(matches!(e, ShapeError::World(_)), "{e}");
    }
}
