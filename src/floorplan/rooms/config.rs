//! The room layer's settings: every length in metres and every area in square metres, each
//! default with its physical reason, turned into cells once from the map's resolution
//! ([`RoomConfig::cells`]) so that the same building gives the same rooms at any cell size.

use super::error::RoomError;

/// The room layer's settings, every length in metres and every area in square metres, each
/// default with its physical reason. A map's resolution turns them into cells once
/// (`RoomConfig::cells`), so that the same building gives the same rooms at any cell size.
///
/// The JSON names carry their unit (`_m`, `_m2`): settings written in cells by an older
/// version are refused by name rather than read as metres.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RoomConfig {
    /// Largest share of occupied cells in the band between two units for their boundary to
    /// count as open. 5 %: a laser's stray hits on a boundary that no wall runs along.
    pub max_wall_share: f64,
    /// Shortest open boundary that joins two units, m; shorter ones are doors. 1.5 m: wider
    /// than the widest single door leaf (1.2 m) with its frame.
    pub min_open_m: f64,
    /// How far through free space the wavefront carries a room's label beyond its units, m.
    /// 1 m: a door's depth and the corners a rectangle misses; farther free space is a room
    /// of its own.
    pub max_reach_m: f64,
    /// Smallest free region beyond every unit's reach that counts as a room, m². 1 m²: a
    /// closet a person can stand in; smaller are specks and scan rays.
    pub min_room_m2: f64,
    /// Half the widest doorway, m: free space narrower than twice this parts the cores of two
    /// rooms. 0.6 m: a door up to 1.2 m wide (a wide single leaf, as building codes allow for
    /// accessible doors) parts two rooms, while a corridor (at least 1.2 m, usually 1.5 m and
    /// more) keeps a core of its own. 0 turns the split off.
    pub door_half_width_m: f64,
    /// Smallest room core a doorway split keeps as a room of its own, m². 2.5 m²: the core of
    /// a room of about 2.8 m x 2.8 m; smaller cores (a nook behind furniture) stay with the
    /// room around them.
    pub min_core_m2: f64,
    /// Free regions beyond every unit's reach are rooms only if a quarter of their
    /// `min_room_m2` lies deeper than this in free space, m. 0.3 m: a person's half-width;
    /// fans of scan rays are thinner. 0 keeps every region.
    pub min_room_depth_m: f64,
    /// Segments smaller than this join the neighbour they share the longest boundary with, m²:
    /// a sliver between two units. 2.5 m², as `min_core_m2`. 0 keeps them.
    pub min_segment_m2: f64,
    /// A door at least this share as wide as the stretch along which its two units face each
    /// other is an opening, not a door. Above 1 no door is.
    pub wide_door_share: f64,
    /// Longest gap between two collinear wall stubs that the doorway split closes, m. 2.5 m:
    /// a double door or the open front of a small office. 0 turns it off.
    pub max_wall_gap_m: f64,
    /// Shortest wall stub on each side of such a gap along its line, m. 0.3 m: longer than a
    /// wall is thick (a wall crossed at right angles is no stub).
    pub min_wall_stub_m: f64,
    /// Smallest extent of a connected occupied part that is a wall, m. 2 m: the side of a
    /// small room; chairs, the legs of a table and a SLAM map's clutter are smaller.
    pub min_wall_len_m: f64,
    /// Whether the clutter inside a room gets the room's label, as a person colours a room on
    /// a floor plan under its furniture (the room layer's `clutter_in_rooms` stage).
    pub clutter_in_rooms: bool,
}

impl Default for RoomConfig {
    fn default() -> Self {
        RoomConfig {
            max_wall_share: 0.05,
            min_open_m: 1.5,
            max_reach_m: 1.0,
            min_room_m2: 1.0,
            door_half_width_m: 0.6,
            min_core_m2: 2.5,
            min_room_depth_m: 0.3,
            min_segment_m2: 2.5,
            wide_door_share: 0.8,
            max_wall_gap_m: 2.5,
            min_wall_stub_m: 0.3,
            min_wall_len_m: 2.0,
            clutter_in_rooms: true,
        }
    }
}

/// How far a wall's drawing strays across its line, m: anti-aliased edges and a wall drawn a
/// cell off its line, three 5 cm cells, as it was set in cells on the benchmark floors. A run
/// of wall no deeper across its line than the wall and the whole cells within this is a stub
/// ([`super::wall_gaps::stub_depth`]): 3 cells at 5 cm, 1 at 10 cm (1.5 cells: a wall cannot
/// stray half a cell), 6 at 2.5 cm.
pub const STUB_NOISE_M: f64 = 0.15;

/// The thickest a piece of wall shorter than [`RoomConfig::min_wall_len_m`] may be, m: 0.2 m,
/// an office wall (10 - 15 cm) with its scanned faces. Such a piece, three times as long as
/// this or more, is a wall ([`super::wall_gaps::walls`]): the wall between a door and a corner,
/// or between a door and a glass pane, is often under 2 m, and read as clutter it left the
/// wall open there (rooms merged with the corridor on generated offices with glass and
/// arches). Chairs, desks and cupboards are blobs, not lines.
pub const WALL_PIECE_THICK_M: f64 = 0.2;

/// How far a hole a scan left in a wall may reach from the wall's seen cells, m, for the
/// wall's pieces on either side of it to be one wall ([`super::wall_gaps::walls`]): 0.1 m, a
/// shiny or dark patch, a pipe or a cable in front of the wall, a laser's miss along a face it
/// grazes; the two 5 cm cells it was set as. Farther, the unseen space is no hole of a wall but
/// space beside it, and clutter would join the unexplored space around the building.
pub const HOLE_REACH_M: f64 = 0.1;

/// How far past its wall ring a unit may run over a seen wall and still be parted by it from
/// the unit beyond, m: 0.5 m, the deepest wall a unit's ring stands for
/// ([`crate::vision::walls::MAX_RING_M`]). The chain may draw a unit's wall in the free space of the
/// room beside it, over the wall it stands for; the band between the two units' rings is then
/// free while the seen wall runs just inside one of them ([`super::pairs`]).
pub const EDGE_STRAY_M: f64 = 0.5;

/// The room layer's settings in cells of one map: [`RoomConfig`] turned into cells once, from
/// the map's resolution ([`RoomConfig::cells`]). The stages of the room layer read these.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct RoomCells {
    /// Largest share of occupied cells in the band between two units for their boundary to
    /// count as open.
    pub max_wall_share: f64,
    /// Shortest open boundary, in cells, that joins two units (shorter ones are doors).
    pub min_open_len: i32,
    /// How far (cells, through free space) the wavefront carries a room's label beyond its
    /// units. Free regions farther from every unit are rooms of their own, numbered after
    /// the units' rooms: a room the chain left unexplained is still a room, not an annex of
    /// its neighbour through the door.
    pub max_reach: u32,
    /// Smallest free region (cells) beyond every unit's reach that counts as a room; smaller
    /// ones (specks, scan rays) are not part of any room.
    pub min_room_cells: usize,
    /// Half the widest doorway, in cells: free space narrower than twice this separates the
    /// cores of two rooms ([`super::segments::split_open_at_doorways`]). 0 turns the split off.
    /// ([`RoomConfig::door_half_width_m`]).
    pub door_half_width: u32,
    /// Smallest room core, in cells, that a doorway split keeps as a room of its own; smaller
    /// cores (a nook behind furniture, the gap between a cupboard and a desk) stay with the
    /// room around them. ([`RoomConfig::min_core_m2`]).
    pub min_core_cells: usize,
    /// Free regions beyond every unit's reach are rooms only if at least `min_room_cells / 4`
    /// of their cells lie deeper than this (cells) in free space: the fans of scan rays a
    /// robot sees through windows and doors are thin, rooms are not. 0 keeps every region.
    pub min_room_depth: u32,
    /// Segments smaller than this (cells) join the neighbour they share the longest boundary
    /// with: a sliver between two units, a nook cut off by a cupboard. 0 keeps them.
    pub min_segment_cells: usize,
    /// A door at least this share as wide as the stretch along which its two units face each
    /// other is an opening, not a door: the units have an open boundary ([`open_pairs`]).
    /// Above 1 no door is.
    pub wide_door_share: f64,
    /// Longest gap, in cells, between two collinear wall stubs that the doorway split closes
    /// ([`super::wall_gaps`]): a room open onto a corridor over its width is closed along the
    /// corridor's wall, as a person draws it. 0 turns it off. ([`RoomConfig::max_wall_gap_m`])
    pub max_wall_gap: u32,
    /// Shortest wall stub, in cells, on each side of such a gap along its line: a wall crossed
    /// at right angles (as thick as a wall) is no stub. ([`RoomConfig::min_wall_stub_m`])
    pub min_wall_stub: u32,
    /// How far, in whole cells, a wall stub's drawing may stray across its line besides the
    /// wall itself ([`super::wall_gaps::stub_depth`]): [`STUB_NOISE_M`], rounded down.
    pub stub_noise: u32,
    /// Smallest extent, in cells, of a connected occupied part that is a wall (its parts
    /// joined through the unseen cells beside them, [`super::wall_gaps`]): chairs, the dots
    /// of a drawn table and the clutter of a SLAM map are no walls. Wall gaps close onto
    /// walls only, a doorway is a narrowing between walls ([`super::segments::split_open_at_doorways`]), and only
    /// walls close the boundary between two units ([`open_pairs`]). ([`RoomConfig::min_wall_len_m`])
    pub min_wall_len: u32,
    /// The thickest a piece of wall may be, in cells ([`WALL_PIECE_THICK_M`], rounded down).
    pub wall_piece_thick: u32,
    /// How far, in cells, an unknown cell may lie from an occupied one and still join the
    /// parts of a wall ([`HOLE_REACH_M`], at least one cell).
    pub hole_reach: u32,
    /// How far past its wall ring a unit may run over a seen wall, in cells ([`EDGE_STRAY_M`]).
    pub edge_stray: u32,
    /// The longest part of a map, in cells, that is a speck ([`super::read::SPECK_M`], one
    /// cell more than fits): the standing test and the passages look past it.
    pub speck: u32,
    /// How deep (chamfer units, 3 per cell) free space must be somewhere along a stretch where
    /// two rooms touch for it to be a passage ([`super::passages::MIN_PASSAGE_M`]).
    pub passage_depth: u32,
    /// Whether the clutter inside a room (occupied parts that are no walls, and unseen specks:
    /// [`RoomCells::min_wall_len`]) gets the room's label, as a person colours a room on a
    /// floor plan under its furniture. Only parts that one room's cells enclose are labelled,
    /// so no two rooms come to touch through clutter. Off, only free cells
    /// are labelled, as the room-segmentation tools of Bormann et al. (2016) do.
    pub clutter_in_rooms: bool,
}

impl Default for RoomCells {
    /// The default settings on a map of 5 cm cells (the benchmark floors' and the generated
    /// floors' cell), for examples and tests that draw their maps in cells.
    fn default() -> Self {
        RoomConfig::default().cells(0.05)
    }
}

/// The longest room-layer settings text read ([`RoomConfig::from_json`]): a dozen fields.
pub const MAX_ROOM_CONFIG_JSON_BYTES: usize = 64 * 1024;

impl RoomConfig {
    /// Room-layer settings from JSON: any subset of the fields (the rest keep their
    /// defaults). Unknown fields, text over [`MAX_ROOM_CONFIG_JSON_BYTES`] and shares outside
    /// their range are refused with a message that names them.
    ///
    /// ```
    /// use ksmcmc::floorplan::rooms::RoomConfig;
    ///
    /// let c = RoomConfig::from_json(r#"{"max_wall_gap_m": 0}"#).unwrap();
    /// assert_eq!((c.max_wall_gap_m, c.min_wall_len_m), (0.0, RoomConfig::default().min_wall_len_m));
    /// let e = RoomConfig::from_json(r#"{"max_wall_gap": 50}"#).unwrap_err();
    /// assert!(e.to_string().contains("unknown field `max_wall_gap`"), "{e}");
    /// let e = RoomConfig::from_json(r#"{"min_wall_len_m": -1}"#).unwrap_err();
    /// assert!(e.to_string().contains("min_wall_len_m"), "{e}");
    /// let e = RoomConfig::from_json(r#"{"max_wall_share": 1.5}"#).unwrap_err();
    /// assert!(e.to_string().contains("max_wall_share"), "{e}");
    /// ```
    pub fn from_json(text: &str) -> Result<RoomConfig, RoomError> {
        if text.len() > MAX_ROOM_CONFIG_JSON_BYTES {
            return Err(RoomError::settings(format!(
                "the room-layer settings are {} bytes, over the limit of {MAX_ROOM_CONFIG_JSON_BYTES} bytes; \
                 they are a dozen fields",
                text.len()
            )));
        }
        let c: RoomConfig = serde_json::from_str(text).map_err(|e| RoomError::settings(e.to_string()))?;
        if !(0.0..=1.0).contains(&c.max_wall_share) {
            return Err(RoomError::settings(format!(
                "max_wall_share is {}: it is a share of the band between two units, from 0 to 1",
                c.max_wall_share
            )));
        }
        for (name, v) in c.lengths() {
            if !(v.is_finite() && (0.0..=MAX_ROOM_LENGTH_M).contains(&v)) {
                return Err(RoomError::settings(format!(
                    "{name} is {v}: give metres (or square metres) from 0 to {MAX_ROOM_LENGTH_M}"
                )));
            }
        }
        if !(c.wide_door_share.is_finite() && c.wide_door_share >= 0.0) {
            return Err(RoomError::settings(format!(
                "wide_door_share is {}: give a share of 0 or more (above 1, no door is an opening)",
                c.wide_door_share
            )));
        }
        Ok(c)
    }

    /// The lengths and areas by their JSON names.
    fn lengths(&self) -> [(&'static str, f64); 10] {
        [
            ("min_open_m", self.min_open_m),
            ("max_reach_m", self.max_reach_m),
            ("min_room_m2", self.min_room_m2),
            ("door_half_width_m", self.door_half_width_m),
            ("min_core_m2", self.min_core_m2),
            ("min_room_depth_m", self.min_room_depth_m),
            ("min_segment_m2", self.min_segment_m2),
            ("max_wall_gap_m", self.max_wall_gap_m),
            ("min_wall_stub_m", self.min_wall_stub_m),
            ("min_wall_len_m", self.min_wall_len_m),
        ]
    }

    /// These settings in cells of `resolution` metres: lengths rounded to whole cells, areas
    /// to whole cells of `resolution`² (a setting above 0 is at least one cell, so that only
    /// 0 turns a stage off). A resolution that is not a positive number is read as 0.05 m.
    pub(crate) fn cells(&self, resolution: f64) -> RoomCells {
        let r = crate::grid::cell_size_m(resolution);
        let count = |v: f64| if v > 0.0 { libm::round(v).max(1.0) } else { 0.0 };
        let len = |m: f64| count(m / r) as u32;
        let area = |m2: f64| count(m2 / (r * r)) as usize;
        RoomCells {
            max_wall_share: self.max_wall_share,
            min_open_len: len(self.min_open_m) as i32,
            max_reach: len(self.max_reach_m),
            min_room_cells: area(self.min_room_m2),
            door_half_width: len(self.door_half_width_m),
            min_core_cells: area(self.min_core_m2),
            min_room_depth: len(self.min_room_depth_m),
            min_segment_cells: area(self.min_segment_m2),
            wide_door_share: self.wide_door_share,
            max_wall_gap: len(self.max_wall_gap_m),
            min_wall_stub: len(self.min_wall_stub_m),
            stub_noise: libm::floor(STUB_NOISE_M / r + 1e-9) as u32,
            min_wall_len: len(self.min_wall_len_m),
            wall_piece_thick: libm::floor(WALL_PIECE_THICK_M / r + 1e-9) as u32,
            hole_reach: len(HOLE_REACH_M),
            edge_stray: len(EDGE_STRAY_M),
            speck: super::read::speck_cells(r),
            passage_depth: super::passages::passage_depth(r),
            clutter_in_rooms: self.clutter_in_rooms,
        }
    }
}

/// The longest length (or largest area) a room-layer setting may have: 10 km, far beyond any
/// building, and few enough cells at any resolution to count in a `u32`.
pub const MAX_ROOM_LENGTH_M: f64 = 10_000.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_become_cells_of_the_maps_resolution() {
        let c = RoomConfig::default();
        assert_eq!((c.cells(0.05).min_wall_len, c.cells(0.05).min_core_cells), (40, 1000));
        assert_eq!((c.cells(0.1).min_wall_len, c.cells(0.1).min_core_cells), (20, 250));
        assert_eq!(c.cells(0.025).door_half_width, 24);
        // A wall stub's drawing noise is 0.15 m in whole cells: three at 5 cm (as it was in
        // cells), one at 10 cm, six at 2.5 cm, three at 4 cm.
        let noise: Vec<u32> = [0.05, 0.1, 0.025, 0.04].iter().map(|&r| c.cells(r).stub_noise).collect();
        assert_eq!(noise, [3, 1, 6, 3]);
        // A setting above 0 is at least one cell; 0 stays 0 and turns its stage off.
        let tiny = RoomConfig { max_wall_gap_m: 0.001, min_wall_stub_m: 0.0, ..c };
        assert_eq!((tiny.cells(0.05).max_wall_gap, tiny.cells(0.05).min_wall_stub), (1, 0));
    }
}
