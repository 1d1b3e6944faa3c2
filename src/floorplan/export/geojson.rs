//! `world.geojson`: the floor plan for indoor-map and floor-plan tools, an RFC 7946
//! FeatureCollection in the shape of Apple's Indoor Mapping Data Format (IMDF, an OGC
//! community standard).
//!
//! | feature | `feature_type` | geometry | properties |
//! |---|---|---|---|
//! | the floor | `level` | Polygon: the map's extent (with anything drawn beyond it) | `category` `unspecified`, `ordinal` 0, `outdoor` false, `name` {"en": "Level 0"}, `short_name` {"en": "0"} |
//! | one per room | `unit` | Polygon, or MultiPolygon if its parts do not touch ([`super::shapes`]) | `category`, `level_id`, `name` (the room's name, `rooms[].name`, else its type and id: {"en": "room 3"}; `alt_name` is then the latter), `display_point` (a Point inside it), `area` (its `area_m2`, free floor m²) |
//! | one per door | `opening` | LineString across the doorway | `category` `pedestrian`, `level_id` |
//!
//! Room types become IMDF unit categories: `room` → `room`, `corridor` → `walkway`, `hall` →
//! `lobby`, `other` and untyped rooms → `unspecified`. The other IMDF properties are written as
//! `null`.
//!
//! **Ids.** IMDF ids are UUIDs. Here they are derived from the world, so that the same world
//! always gives the same ids and an id says which room or door it is: RFC 9562 version 8
//! (custom) UUIDs `6b736d63-6d63-8KKK-8SSS-NNNNNNNNNNNN`, where `6b736d63-6d63` spells "ksmcmc",
//! `KKK` is the feature kind (hex: 000 level, 001 unit, 002 opening), `NNNNNNNNNNNN` the room
//! or door id in hex, and `SSS` 0 unless several doors share an id (then their order among
//! them). Room 3 is `6b736d63-6d63-8001-8000-000000000003`.
//!
//! **Coordinates** are metres in the map's frame, with the ROS origin of its `map.yaml`
//! applied, or longitude and latitude with a [`Georef`] (see [`super::georef`]). Rings are
//! closed, exteriors counter-clockwise and holes clockwise (RFC 7946's right-hand rule), with
//! millimetres kept (more decimals for finer maps; about as fine in degrees).
//!
//! Each feature is one line of the file, so that files diff well.

use super::georef::{Georef, MapOrigin};
use super::shapes::{floor_shapes, FloorShapes, MapPoint, MapPolygon, ShapeError};
use crate::floorplan::world::{UnitType, World};
use crate::grid::{Grid, OccupancyMap};
use serde_json::{json, Value};

/// `world.geojson` of `world` (with its room layer) on `map`, with `labels` its room labels
/// (`labels.pgm`), in metres of the map frame or, with `georef`, in longitude and latitude.
///
/// ```
/// use ksmcmc::floorplan::geojson::world_geojson;
/// use ksmcmc::floorplan::{Room, Unit, UnitType, World};
/// use ksmcmc::grid::{Cell, Grid, OccupancyMap};
///
/// let map = OccupancyMap::from_classified(Grid::new(21, 11, Cell::Free));
/// let mut world = World::empty(21, 11);
/// world.units.push(Unit::new(1, 0, 0, 21, 11, UnitType::Corridor));
/// world.rooms.push(Room { id: 1, kind: UnitType::Corridor, units: vec![1], area_m2: 0.4, doors: vec![], opens_to: vec![], name: None });
/// let text = world_geojson(&world, &Grid::new(21, 11, 1), &map, None)?;
/// let fc: serde_json::Value = serde_json::from_str(&text).unwrap();
/// let unit = &fc["features"][1];
/// assert_eq!(unit["feature_type"], "unit");
/// assert_eq!(unit["properties"]["category"], "walkway");
/// // 5 cm cells: the floor from cell 0.5 to 20.5 is 0.025 m to 1.025 m, y up from the bottom.
/// assert_eq!(unit["geometry"]["coordinates"][0][0], serde_json::json!([0.025, 0.525]));
/// # Ok::<(), ksmcmc::floorplan::shapes::ShapeError>(())
/// ```
pub fn world_geojson(
    world: &World,
    labels: &Grid<u16>,
    map: &OccupancyMap,
    georef: Option<&Georef>,
) -> Result<String, ShapeError> {
    Ok(geojson(&floor_shapes(world, labels)?, &MapOrigin::of(map), georef))
}

/// The IMDF unit category of a room type.
pub fn unit_category(kind: UnitType) -> &'static str {
    match kind {
        UnitType::Room => "room",
        UnitType::Corridor => "walkway",
        UnitType::Hall => "lobby",
        UnitType::Other | UnitType::Unknown => "unspecified",
    }
}

/// The id of a feature: see the module docs. `kind`: 0 level, 1 unit, 2 opening; `seq`: the
/// feature's order among those of its kind sharing `id`.
pub fn feature_id(kind: u16, seq: u32, id: u32) -> String {
    // 14 bits of `seq` in the variant field, the rest beside the kind.
    let (high, low) = (seq >> 14, seq & 0x3fff);
    format!("6b736d63-6d63-8{:03x}-{:04x}-{id:012x}", (kind as u32 & 0xf) | (high & 0xff) << 4, 0x8000 | low)
}

/// `world.geojson` of shapes made by [`floor_shapes`], placed with `origin` and `georef`.
pub fn geojson(shapes: &FloorShapes, origin: &MapOrigin, georef: Option<&Georef>) -> String {
    let out = Projection::new(origin, georef);
    let level_id = feature_id(0, 0, 0);
    let mut features = vec![level(shapes, &out, &level_id)];
    for room in &shapes.rooms {
        let geometry = out.geometry(&room.polygons);
        // A person's name for the room, with the generated one as its alternative.
        let label = format!("{} {}", room.kind.name(), room.id);
        let (name, alt_name) = match &room.name {
            Some(n) => (json!({"en": n}), json!({"en": label})),
            None => (json!({"en": label}), Value::Null),
        };
        features.push(feature(
            feature_id(1, 0, room.id),
            "unit",
            geometry,
            json!({
                "category": unit_category(room.kind),
                "restriction": null,
                "accessibility": null,
                "name": name,
                "alt_name": alt_name,
                "display_point": {"type": "Point", "coordinates": out.point(room.anchor)},
                "level_id": level_id,
                "area": round(room.area_m2, 3),
            }),
        ));
    }
    let mut seen: std::collections::HashMap<u32, u32> = std::collections::HashMap::new();
    for door in &shapes.doors {
        let seq = seen.entry(door.id).or_insert(0);
        let coordinates: Vec<Value> = door.ends.iter().map(|&p| out.point(p)).collect();
        features.push(feature(
            feature_id(2, *seq, door.id),
            "opening",
            json!({"type": "LineString", "coordinates": coordinates}),
            json!({
                "category": "pedestrian",
                "accessibility": null,
                "access_control": null,
                "door": null,
                "name": null,
                "alt_name": null,
                "display_point": null,
                "level_id": level_id,
            }),
        ));
        *seq += 1;
    }
    format!("{{\"type\":\"FeatureCollection\",\"features\":[\n{}\n]}}\n", features.join(",\n"))
}

/// A feature with its members in the usual order: type, id, feature_type, geometry, properties.
fn feature(id: String, feature_type: &str, geometry: Value, properties: Value) -> String {
    let text = |v: &Value| serde_json::to_string(v).expect("JSON values serialise");
    format!(
        "{{\"type\":\"Feature\",\"id\":{},\"feature_type\":{},\"geometry\":{},\"properties\":{}}}",
        text(&id.into()),
        text(&feature_type.into()),
        text(&geometry),
        text(&properties)
    )
}

/// The level: the map's extent, widened to anything drawn beyond it.
fn level(shapes: &FloorShapes, out: &Projection, id: &str) -> String {
    let [w, h] = shapes.map_size.map(f64::from);
    let mut b = [0.0, 0.0, w, h];
    let points = shapes.rooms.iter().flat_map(|r| r.polygons.iter()).flat_map(|p| p.exterior.iter());
    for &(x, y) in points.chain(shapes.doors.iter().flat_map(|d| d.ends.iter())) {
        b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
    }
    let extent = MapPolygon { exterior: vec![(b[0], b[1]), (b[0], b[3]), (b[2], b[3]), (b[2], b[1])], holes: vec![] };
    feature(
        id.to_string(),
        "level",
        out.geometry(std::slice::from_ref(&extent)),
        json!({
            "category": "unspecified",
            "restriction": null,
            "outdoor": false,
            "ordinal": 0,
            "name": {"en": "Level 0"},
            "short_name": {"en": "0"},
            "display_point": null,
            "address_id": null,
            "building_ids": null,
        }),
    )
}

/// From map points to output coordinates, rounded.
struct Projection<'a> {
    origin: &'a MapOrigin,
    georef: Option<&'a Georef>,
    decimals: i32,
}

impl<'a> Projection<'a> {
    fn new(origin: &'a MapOrigin, georef: Option<&'a Georef>) -> Projection<'a> {
        // Enough decimals for a twentieth of a cell, at least millimetres; about 10^5 times
        // finer in degrees (a degree of latitude is 111 km).
        let mut decimals = 3;
        while decimals < 9 && libm::pow(10.0, -(decimals as f64)) > origin.resolution / 20.0 {
            decimals += 1;
        }
        Projection { origin, georef, decimals: if georef.is_some() { decimals + 5 } else { decimals } }
    }

    fn xy(&self, p: MapPoint) -> (f64, f64) {
        let (x, y) = self.origin.to_metres(p);
        let (x, y) = match self.georef {
            Some(g) => g.lon_lat(x, y),
            None => (x, y),
        };
        (round(x, self.decimals), round(y, self.decimals))
    }

    fn point(&self, p: MapPoint) -> Value {
        let (x, y) = self.xy(p);
        json!([x, y])
    }

    /// A closed ring, counter-clockwise (`ccw`) or clockwise in output coordinates, without
    /// repeated points; `None` if fewer than three points are left.
    fn ring(&self, ring: &[MapPoint], ccw: bool) -> Option<Vec<(f64, f64)>> {
        let mut pts: Vec<(f64, f64)> = ring.iter().map(|&p| self.xy(p)).collect();
        pts.dedup();
        while pts.len() > 1 && pts.first() == pts.last() {
            pts.pop();
        }
        if pts.len() < 3 {
            return None;
        }
        let area2: f64 = (0..pts.len())
            .map(|k| {
                let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
                a.0 * b.1 - b.0 * a.1
            })
            .sum();
        if (area2 > 0.0) != ccw {
            pts.reverse();
        }
        pts.push(pts[0]);
        Some(pts)
    }

    /// Polygon, MultiPolygon or `null` (no polygons).
    fn geometry(&self, polygons: &[MapPolygon]) -> Value {
        let polys: Vec<Value> = polygons
            .iter()
            .filter_map(|p| {
                let exterior = self.ring(&p.exterior, true)?;
                let rings = std::iter::once(exterior).chain(p.holes.iter().filter_map(|h| self.ring(h, false)));
                Some(Value::Array(rings.map(|r| json!(r.iter().map(|&(x, y)| [x, y]).collect::<Vec<_>>())).collect()))
            })
            .collect();
        match polys.len() {
            0 => Value::Null,
            1 => json!({"type": "Polygon", "coordinates": polys[0]}),
            _ => json!({"type": "MultiPolygon", "coordinates": polys}),
        }
    }
}

/// `v` rounded to `decimals`, without a negative zero.
fn round(v: f64, decimals: i32) -> f64 {
    let s = libm::pow(10.0, decimals as f64);
    let r = libm::round(v * s) / s;
    if r == 0.0 {
        0.0
    } else {
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_version_8_uuids_that_name_the_feature() {
        assert_eq!(feature_id(1, 0, 3), "6b736d63-6d63-8001-8000-000000000003");
        assert_eq!(feature_id(2, 1, 0xabc), "6b736d63-6d63-8002-8001-000000000abc");
        assert_eq!(feature_id(2, 0x4001, u32::MAX), "6b736d63-6d63-8012-8001-0000ffffffff");
        assert_eq!(feature_id(0, 0, 0), "6b736d63-6d63-8000-8000-000000000000");
    }

    #[test]
    fn categories_follow_imdf() {
        let c: Vec<&str> = UnitType::ALL.iter().map(|&k| unit_category(k)).collect();
        assert_eq!(c, ["room", "walkway", "lobby", "unspecified", "unspecified"]);
    }

    #[test]
    fn rounding_keeps_millimetres_and_more_for_fine_maps() {
        let o = MapOrigin { resolution: 0.05, origin: [0.0; 3], height: 10 };
        assert_eq!(Projection::new(&o, None).decimals, 3);
        let fine = MapOrigin { resolution: 0.001, ..o };
        assert_eq!(Projection::new(&fine, None).decimals, 5);
        let g = Georef::new(50.0, 8.0, 0.0).unwrap();
        assert_eq!(Projection::new(&o, Some(&g)).decimals, 8);
        assert_eq!(round(-0.0001, 3), 0.0);
        assert!(round(-0.0001, 3).is_sign_positive());
        assert_eq!(round(1.23456, 3), 1.235);
    }
}
