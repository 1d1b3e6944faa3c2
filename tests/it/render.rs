//! Pixel tests for `ksmcmc::render`: map colours, world overlays, frames, labels, PNG output,
//! and every real map in `shared/datasets` (skipped without it) or generated stand-ins.

use ksmcmc::floorplan::{Door, Frame, UnexplainedArea, Unit, UnitType, World};
use ksmcmc::grid::{Cell, Grid, OccupancyMap};
use ksmcmc::render::{
    self, cell_rgb, draw_labels, draw_map, encode_png, font, label_rgb, label_text_scale, render, room_fill_rgb,
    to_rgba, try_render, RenderError, RenderOptions, DOOR_RGBA, LABEL_TEXT_RGBA, MAX_PIXELS, UNEXPLAINED_RGBA,
    WALL_RGBA,
};
use tiny_skia::Pixmap;

const BLUE: [u8; 3] = [WALL_RGBA[0], WALL_RGBA[1], WALL_RGBA[2]];
const CYAN: [u8; 3] = [DOOR_RGBA[0], DOOR_RGBA[1], DOOR_RGBA[2]];
const WHITE: [u8; 3] = [255, 255, 255];
const BLACK: [u8; 3] = [0, 0, 0];

/// The straight RGB of a pixel; panics off the pixmap (a test bug).
fn rgb(pixmap: &Pixmap, x: u32, y: u32) -> [u8; 3] {
    let p = pixmap.pixel(x, y).expect("pixel on the pixmap").demultiply();
    [p.red(), p.green(), p.blue()]
}

fn no_labels(scale: u32) -> RenderOptions {
    RenderOptions { scale, labels: false, legend: false }
}

/// A 16x12 map: free everywhere except an occupied cell at (12, 2), unknown cells at (13, 2),
/// (3, 3) and (4, 3), and an occupied cell at (5, 3).
fn small_map() -> Grid<Cell> {
    let mut g = Grid::new(16, 12, Cell::Free);
    *g.at_mut(12, 2) = Cell::Occupied;
    *g.at_mut(13, 2) = Cell::Unknown;
    *g.at_mut(3, 3) = Cell::Unknown;
    *g.at_mut(4, 3) = Cell::Unknown;
    *g.at_mut(5, 3) = Cell::Occupied;
    g
}

/// Unit 1 covers cells (1..9, 1..8); unit 2 (8..15, 1..8) shares its column 8 wall. A door runs
/// down that wall from (8, 3) to (8, 5). Object cells: (3, 3) unknown, (4, 3) unknown, (5, 3)
/// occupied, (6, 3) free.
fn small_world() -> World {
    let mut w = World::empty(16, 12);
    w.units.push(Unit::new(1, 1, 1, 8, 7, UnitType::Room));
    w.units.push(Unit::new(2, 8, 1, 7, 7, UnitType::Corridor));
    w.doors.push(Door { id: 1, units: [1, 2], x0: 8, y0: 3, x1: 8, y1: 5, opening: false });
    w.object_cells = vec![[3, 3], [4, 3], [5, 3], [6, 3]];
    w.validate().expect("the test world is valid");
    w
}

fn is_green_tinted(c: [u8; 3]) -> bool {
    let [r, g, b] = c;
    g as i32 > r as i32 + 60 && g as i32 > b as i32 + 60
}

#[test]
fn map_and_world_have_the_papers_colours() {
    let map = small_map();
    let pixmap = render(&map, Some(&small_world()), &no_labels(1));
    assert_eq!((pixmap.width(), pixmap.height()), (16, 12));

    // Walls: the outer ring of both units.
    for (x, y) in [(1, 1), (8, 1), (1, 7), (4, 7), (1, 4), (14, 4), (14, 1), (11, 7)] {
        assert_eq!(rgb(&pixmap, x, y), BLUE, "wall cell ({x}, {y})");
    }
    // Doors over the walls.
    for y in 3..=5 {
        assert_eq!(rgb(&pixmap, 8, y), CYAN, "door cell (8, {y})");
    }
    assert_eq!(rgb(&pixmap, 8, 2), BLUE, "the wall just above the door stays a wall");
    assert_eq!(rgb(&pixmap, 8, 6), BLUE, "the wall just below the door stays a wall");
    // Object cells: green over whatever class lies beneath, still telling the classes apart.
    let objects: Vec<[u8; 3]> = (3..=6).map(|x| rgb(&pixmap, x, 3)).collect();
    for (x, c) in (3..=6).zip(&objects) {
        assert!(is_green_tinted(*c), "object cell ({x}, 3) is {c:?}");
    }
    assert_eq!(objects[0], objects[1], "two unknown object cells look alike");
    assert!(objects[2][1] < objects[0][1], "occupied under green is darker than unknown");
    assert!(objects[0][1] < objects[3][1], "unknown under green is darker than free");
    // Interiors are tinted by type: a free cell shows the tint exactly, an occupied one stays
    // black, an unknown one is the gray times the tint (darker than the tint, still a tint).
    let room = room_fill_rgb(UnitType::Room);
    let corridor = room_fill_rgb(UnitType::Corridor);
    assert_ne!(room, corridor);
    assert_eq!(rgb(&pixmap, 4, 4), room, "free inside the room");
    assert_eq!(rgb(&pixmap, 2, 6), room, "free inside the room, by its wall");
    assert_eq!(rgb(&pixmap, 11, 4), corridor, "free inside the corridor");
    assert_eq!(rgb(&pixmap, 12, 2), BLACK, "occupied inside the corridor stays black");
    let unknown = rgb(&pixmap, 13, 2);
    for k in 0..3 {
        let expected = cell_rgb(Cell::Unknown)[k] as i32 * corridor[k] as i32 / 255;
        assert!((unknown[k] as i32 - expected).abs() <= 1, "unknown under the tint is {unknown:?}");
    }
    // The map where no world is drawn.
    assert_eq!(rgb(&pixmap, 0, 0), WHITE, "free outside every unit");
    assert_eq!(rgb(&pixmap, 15, 11), WHITE, "far corner");
    assert!(pixmap.pixels().iter().all(|p| p.alpha() == 255), "the picture is opaque");
}

#[test]
fn unexplained_areas_are_tinted_orange_exactly_on_their_runs() {
    let map = small_map();
    let mut world = small_world();
    // Free cells below both units: rows 9 and 10, an L of 3 + 1 cells.
    world.unexplained.push(UnexplainedArea {
        id: 1,
        cells: 4,
        x0: 2,
        y0: 9,
        x1: 4,
        y1: 10,
        runs: vec![[9, 2, 4], [10, 4, 4]],
    });
    world.validate().unwrap();
    let pixmap = render(&map, Some(&world), &no_labels(1));
    let [r, g, b, a] = UNEXPLAINED_RGBA;
    let blend = |bg: u8, fg: u8| ((fg as u32 * a as u32 + bg as u32 * (255 - a as u32)) as f64 / 255.0) as i32;
    let expected = [blend(255, r), blend(255, g), blend(255, b)];
    for (x, y) in [(2, 9), (3, 9), (4, 9), (4, 10)] {
        let c = rgb(&pixmap, x, y);
        for k in 0..3 {
            assert!((c[k] as i32 - expected[k]).abs() <= 1, "({x}, {y}) is {c:?}, expected about {expected:?}");
        }
    }
    for (x, y) in [(1, 9), (5, 9), (2, 10), (3, 10), (4, 11), (4, 8)] {
        assert_eq!(rgb(&pixmap, x, y), WHITE, "({x}, {y}) is not in the area");
    }
}

#[test]
fn map_without_world_is_cell_rgb() {
    let map = small_map();
    let pixmap = draw_map(&map);
    for y in 0..map.height() {
        for x in 0..map.width() {
            assert_eq!(rgb(&pixmap, x as u32, y as u32), cell_rgb(*map.at(x, y)), "cell ({x}, {y})");
        }
    }
    assert_eq!(render(&map, None, &RenderOptions::default()).data(), pixmap.data());
}

#[test]
fn scale_repeats_every_cell_as_a_block() {
    let map = small_map();
    let world = small_world();
    let one = render(&map, Some(&world), &no_labels(1));
    let three = render(&map, Some(&world), &no_labels(3));
    assert_eq!((three.width(), three.height()), (48, 36));
    for y in 0..three.height() {
        for x in 0..three.width() {
            assert_eq!(rgb(&three, x, y), rgb(&one, x / 3, y / 3), "pixel ({x}, {y})");
        }
    }
}

/// Where a world point is relative to a unit's wall ring, with a safety margin in cells.
#[derive(Debug, PartialEq)]
enum Side {
    Wall,
    /// Clearly inside the ring: the tinted interior.
    Inside,
    /// Clearly outside the unit.
    Outside,
    Edge,
}

fn ring_side(u: &Unit, x: f64, y: f64, m: f64) -> Side {
    let inside = |x0: f64, y0: f64, x1: f64, y1: f64, grow: f64| {
        x > x0 - grow && x < x1 + grow && y > y0 - grow && y < y1 + grow
    };
    let (x0, y0, x1, y1) = (u.x as f64, u.y as f64, (u.x + u.w) as f64, (u.y + u.h) as f64);
    let in_outer = |g| inside(x0, y0, x1, y1, g);
    let in_inner = |g| inside(x0 + 1.0, y0 + 1.0, x1 - 1.0, y1 - 1.0, g);
    if in_outer(-m) && !in_inner(m) {
        Side::Wall
    } else if !in_outer(m) {
        Side::Outside
    } else if in_inner(-m) {
        Side::Inside
    } else {
        Side::Edge
    }
}

#[test]
fn rotated_frame_draws_walls_where_the_frame_puts_them() {
    let (w, h, scale) = (60usize, 50usize, 4u32);
    let map = Grid::new(w, h, Cell::Free);
    let mut world = World::empty(w as u32, h as u32);
    world.frame = Frame { angle: 0.3, world_size: [64, 56], map_size: [w as u32, h as u32] };
    let unit = Unit::new(1, 22, 20, 20, 14, UnitType::Room);
    world.units.push(unit);
    world.validate().expect("valid world");
    let pixmap = render(&map, Some(&world), &no_labels(scale));

    // Every pixel whose centre lies clearly on the rotated ring is blue, every pixel clearly
    // inside it has the room tint, every pixel clearly outside the unit is untouched white.
    let (mut walls, mut others) = (0, 0);
    let tint = room_fill_rgb(UnitType::Room);
    for py in 0..pixmap.height() {
        for px in 0..pixmap.width() {
            let (mx, my) = ((px as f64 + 0.5) / scale as f64, (py as f64 + 0.5) / scale as f64);
            let (wx, wy) = world.frame.to_world(mx, my);
            match ring_side(&unit, wx, wy, 0.3) {
                Side::Wall => {
                    walls += 1;
                    assert_eq!(rgb(&pixmap, px, py), BLUE, "pixel ({px}, {py}) is on the wall")
                }
                Side::Inside => {
                    others += 1;
                    assert_eq!(rgb(&pixmap, px, py), tint, "pixel ({px}, {py}) is inside the unit")
                }
                Side::Outside => {
                    others += 1;
                    assert_eq!(rgb(&pixmap, px, py), WHITE, "pixel ({px}, {py}) is outside the unit")
                }
                Side::Edge => {}
            }
        }
    }
    assert!(walls > 300 && others > 40_000, "the test saw {walls} wall and {others} other pixels");

    // Spot checks stated through Frame::to_map: the middle of the top wall cell row is blue...
    let (mx, my) = world.frame.to_map(32.5, 20.5);
    assert_eq!(rgb(&pixmap, (mx * 4.0) as u32, (my * 4.0) as u32), BLUE);
    // ...the identity position of the unit's top-left corner is not (the frame moved it)...
    let (wx, wy) = world.frame.to_world(22.5, 20.5);
    // (it lies inside the moved unit, so it has the room tint)...
    assert_eq!(ring_side(&unit, wx, wy, 0.3), Side::Inside);
    assert_eq!(rgb(&pixmap, 22 * 4 + 2, 20 * 4 + 2), tint);
    // ...and a far corner is untouched.
    assert_eq!(rgb(&pixmap, 1, 1), WHITE);
    assert_eq!(rgb(&pixmap, pixmap.width() - 1, pixmap.height() - 1), WHITE);
}

#[test]
fn rotated_doors_and_objects_follow_the_frame() {
    let map = Grid::new(40, 40, Cell::Free);
    let mut world = World::empty(40, 40);
    world.frame.angle = -0.5;
    world.units.push(Unit::new(1, 5, 5, 15, 30, UnitType::Room));
    world.units.push(Unit::new(2, 19, 5, 15, 30, UnitType::Room));
    world.doors.push(Door { id: 1, units: [1, 2], x0: 19, y0: 15, x1: 19, y1: 20, opening: false });
    world.object_cells = vec![[10, 25], [11, 25]];
    world.validate().expect("valid world");
    let pixmap = render(&map, Some(&world), &no_labels(5));
    let at = |x: f64, y: f64| {
        let (mx, my) = world.frame.to_map(x, y);
        rgb(&pixmap, (mx * 5.0) as u32, (my * 5.0) as u32)
    };
    assert_eq!(at(19.5, 17.5), CYAN);
    assert_eq!(at(19.5, 12.5), BLUE);
    assert!(is_green_tinted(at(10.5, 25.5)));
    assert_eq!(at(12.5, 25.5), room_fill_rgb(UnitType::Room), "free inside unit 1: the room tint");
    assert_eq!(rgb(&pixmap, 0, 0), WHITE, "outside every unit");
}

#[test]
fn labels_draw_at_the_unit_centre_and_only_when_asked() {
    let map = Grid::new(80, 40, Cell::Occupied);
    let mut world = World::empty(80, 40);
    world.units.push(Unit::new(3, 10, 5, 40, 30, UnitType::Room));
    let plain = render(&map, Some(&world), &no_labels(2));
    let labelled = render(&map, Some(&world), &RenderOptions { scale: 2, labels: true, legend: false });
    assert_eq!(render(&map, Some(&world), &no_labels(2)).data(), plain.data());

    // The unit's centre is cell (30, 20), pixel (60, 40); "room 3" is 6 characters.
    let factor = label_text_scale(2);
    let (text_w, text_h) = font::text_size("room 3", factor);
    let (cx, cy) = (60i64, 40i64);
    let mut changed = 0;
    let mut text_pixels = 0;
    for y in 0..plain.height() {
        for x in 0..plain.width() {
            if rgb(&plain, x, y) == rgb(&labelled, x, y) {
                continue;
            }
            changed += 1;
            let (dx, dy) = ((x as i64 - cx).abs(), (y as i64 - cy).abs());
            assert!(
                dx <= text_w as i64 / 2 + 2 * factor as i64 && dy <= text_h as i64 / 2 + 2 * factor as i64,
                "pixel ({x}, {y}) changed, far from the centre"
            );
            if rgb(&labelled, x, y) == [LABEL_TEXT_RGBA[0], LABEL_TEXT_RGBA[1], LABEL_TEXT_RGBA[2]] {
                text_pixels += 1;
            }
        }
    }
    assert!(changed as u32 >= text_w * text_h / 2, "only {changed} pixels changed");
    assert!(text_pixels > 50, "only {text_pixels} pixels of text colour");
    // The box is light, so a label on a black map is readable: the pixel at the centre of the
    // box's padding, left of the text, is bright.
    let pad_x = (cx - text_w as i64 / 2 - factor as i64 / 2) as u32;
    assert!(rgb(&labelled, pad_x, cy as u32).iter().all(|&c| c > 180));
}

#[test]
fn labels_are_readable_at_every_scale() {
    for scale in 1..=16 {
        let glyph_px = label_text_scale(scale) * font::CAP_HEIGHT;
        assert!(glyph_px >= 10, "capitals are {glyph_px} px at scale {scale}");
    }
    assert_eq!(render::unit_label(&Unit::new(12, 0, 0, 3, 3, UnitType::Corridor)), "corridor 12");
}

#[test]
fn font_covers_printable_ascii() {
    let mut seen = std::collections::HashSet::new();
    for c in ' '..='~' {
        let g = font::glyph(c).unwrap_or_else(|| panic!("no glyph for {c:?}"));
        assert!(g.iter().all(|row| *row < 1 << font::GLYPH_WIDTH), "{c:?} is wider than the cell");
        assert_eq!(c == ' ', g.iter().all(|row| *row == 0), "{c:?} has ink unless it is a space");
        assert!(seen.insert(*g), "{c:?} looks like another character");
        assert_ne!(*g, font::PLACEHOLDER, "{c:?} is drawn as the placeholder");
    }
    for c in ['é', 'ß', '\n', '\t', '\u{7f}', '\u{1F600}'] {
        assert_eq!(font::glyph(c), None, "{c:?}");
        assert_eq!(font::glyph_or_placeholder(c), &font::PLACEHOLDER);
    }
}

/// Draws `text` at factor 2 on a 60x20 transparent pixmap at (2, 2).
fn draw(text: &str) -> Pixmap {
    let mut p = Pixmap::new(60, 20).expect("pixmap");
    font::draw_text(&mut p, 2, 2, text, 2, [0, 0, 0, 255]);
    p
}

#[test]
fn unknown_characters_draw_a_placeholder_box() {
    let pixmap = draw("é");
    assert_eq!(pixmap.data(), draw("\u{1F600}").data());
    // Font pixel (col, row) covers output pixels (2 + 2 col .., 2 + 2 row ..).
    let inked = |col: u32, row: u32| pixmap.pixel(2 + 2 * col, 2 + 2 * row).map(|p| p.alpha()) == Some(255);
    for row in 0..font::GLYPH_HEIGHT {
        for col in 0..font::GLYPH_WIDTH {
            let expected = font::PLACEHOLDER[row as usize] & (1 << (font::GLYPH_WIDTH - 1 - col)) != 0;
            assert_eq!(inked(col, row), expected, "font pixel ({col}, {row})");
        }
    }
    assert!(inked(0, 0) && inked(4, 6) && !inked(2, 3), "a hollow box");
    // The box takes a character's place: the next character sits one advance further.
    assert_eq!(
        draw("éA").data(),
        {
            let mut p = draw("é");
            font::draw_text(&mut p, 2 + 2 * font::ADVANCE as i32, 2, "A", 2, [0, 0, 0, 255]);
            p
        }
        .data()
    );
}

#[test]
fn text_is_clipped_not_panicking() {
    let mut p = Pixmap::new(10, 10).expect("pixmap");
    for (x, y) in [(-5, -5), (-1000, 3), (8, 8), (i32::MAX, i32::MAX), (i32::MIN, i32::MIN), (0, -15)] {
        font::draw_text(&mut p, x, y, "Hello, world!", 3, [0, 0, 0, 255]);
    }
    font::draw_text(&mut p, 0, 0, "x", 0, [0, 0, 0, 255]);
    font::draw_text(&mut p, 0, 0, "", 1, [0, 0, 0, 255]);
    // (-5, -5) at factor 3: the `H`'s right stem (font column 4) covers pixels 7..10 of rows 0..16.
    assert_eq!(p.pixel(8, 0).map(|c| c.alpha()), Some(255));
    assert_eq!(font::text_size("", 3), (0, 24));
    assert_eq!(font::text_size("ab", 1), (11, 8));
}

#[test]
fn rgba_has_four_straight_bytes_per_pixel() {
    let pixmap = render(&small_map(), Some(&small_world()), &no_labels(2));
    let rgba = to_rgba(&pixmap);
    assert_eq!(rgba.len(), 4 * pixmap.width() as usize * pixmap.height() as usize);
    // Pixel (2, 2) is wall cell (1, 1).
    let i = 4 * (2 * pixmap.width() as usize + 2);
    assert_eq!(rgba[i..i + 4], [BLUE[0], BLUE[1], BLUE[2], 255]);
}

#[test]
fn png_round_trips() {
    let map = small_map();
    let pixmap = render(&map, None, &no_labels(2));
    let png = encode_png(&pixmap);
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"));
    let back = Pixmap::decode_png(&png).expect("our PNG decodes");
    assert_eq!(back.data(), pixmap.data(), "lossless");
    // The map loader reads the picture back to the same classes, at the output size.
    let loaded = OccupancyMap::from_bytes(&png).expect("the map loader reads our PNG");
    assert_eq!((loaded.width(), loaded.height()), (32, 24));
    for y in 0..24 {
        for x in 0..32 {
            assert_eq!(loaded.classified().at(x, y), map.at(x / 2, y / 2), "cell ({x}, {y})");
        }
    }
    // With a world drawn in, the size still round-trips.
    let with_world = encode_png(&render(&map, Some(&small_world()), &RenderOptions::default()));
    let loaded = OccupancyMap::from_bytes(&with_world).expect("PNG with a world");
    assert_eq!((loaded.width(), loaded.height()), (16, 12));
}

#[test]
fn same_inputs_give_identical_bytes() {
    let options = RenderOptions { scale: 3, labels: true, legend: true };
    let mut world = small_world();
    world.frame.angle = 0.2;
    let a = render(&small_map(), Some(&world), &options);
    let b = render(&small_map(), Some(&world.clone()), &options.clone());
    assert_eq!(a.data(), b.data());
    assert_eq!(encode_png(&a), encode_png(&b));
    assert_ne!(encode_png(&a), encode_png(&render(&small_map(), Some(&small_world()), &options)));
}

#[test]
fn label_regions_get_distinct_deterministic_colours() {
    let colours: Vec<[u8; 3]> = (1..=64).map(label_rgb).collect();
    for (i, a) in colours.iter().enumerate() {
        for (j, b) in colours.iter().enumerate().skip(i + 1) {
            let d: i32 = a.iter().zip(b).map(|(x, y)| (*x as i32 - *y as i32).abs()).sum();
            assert!(d >= 24, "labels {} and {} look alike: {a:?} {b:?}", i + 1, j + 1);
        }
    }
    assert_eq!(label_rgb(7), label_rgb(7));

    let map = Grid::new(4, 2, Cell::Occupied);
    let labels = Grid::from_vec(4, 2, vec![0, 1, 2, 2, 0, 1, 300, 0]).expect("grid");
    let mut pixmap = render(&map, None, &no_labels(2));
    draw_labels(&mut pixmap, &labels, 2, 255);
    assert_eq!(rgb(&pixmap, 0, 0), BLACK, "label 0 is not drawn");
    assert_eq!(rgb(&pixmap, 3, 1), label_rgb(1), "cell (1, 0) is label 1 in all its pixels");
    assert_eq!(rgb(&pixmap, 5, 1), label_rgb(2));
    assert_eq!(rgb(&pixmap, 5, 1), rgb(&pixmap, 7, 0), "one label, one colour");
    assert_eq!(rgb(&pixmap, 4, 2), label_rgb(300));

    // Half opacity over black is about half the colour.
    let mut half = render(&map, None, &no_labels(1));
    draw_labels(&mut half, &labels, 1, 128);
    let [r, g, b] = rgb(&half, 1, 0);
    let [lr, lg, lb] = label_rgb(1);
    for (c, l) in [(r, lr), (g, lg), (b, lb)] {
        assert!((c as i32 - l as i32 / 2).abs() <= 2, "{c} vs {l}");
    }

    // A label grid of the wrong size, or a zero scale, draws what fits without panicking.
    let big = Grid::new(100, 100, 5u16);
    let mut small = render(&map, None, &no_labels(1));
    draw_labels(&mut small, &big, 1, 255);
    assert_eq!(rgb(&small, 3, 1), label_rgb(5));
    draw_labels(&mut small, &big, 0, 255);
    draw_labels(&mut small, &big, 7, 255);
}

#[test]
fn sizes_are_checked_not_panicking() {
    let empty: Grid<Cell> = Grid::new(0, 7, Cell::Free);
    assert_eq!(try_render(&empty, None, &no_labels(1)).err(), Some(RenderError::Empty { width: 0, height: 7 }));
    let p = draw_map(&empty);
    assert_eq!((p.width(), p.height()), (1, 1));

    let map = small_map();
    assert_eq!(try_render(&map, None, &no_labels(0)).err(), Some(RenderError::ZeroScale));
    let p = render(&map, None, &no_labels(0));
    assert_eq!((p.width(), p.height()), (16, 12), "scale 0 draws at scale 1");

    // 16x12 cells fit MAX_PIXELS = 2^26 up to scale 591 (591^2 * 192 <= 2^26 < 592^2 * 192).
    assert_eq!(render::max_scale(16, 12), 591);
    assert!(try_render(&map, None, &no_labels(591)).is_ok());
    let err = try_render(&map, None, &no_labels(592)).unwrap_err();
    assert!(matches!(err, RenderError::TooLarge { max_scale: 591, .. }), "{err:?}");
    assert!(err.to_string().contains("at most 591"), "{err}");
    let p = render(&map, None, &no_labels(u32::MAX));
    assert_eq!((p.width(), p.height()), (16 * 591, 12 * 591), "render lowers the scale");
    assert!(p.width() as u64 * p.height() as u64 <= MAX_PIXELS);

    // Every map the loaders accept by default fits at scale 1.
    assert!(ksmcmc::grid::DEFAULT_MAX_CELLS as u64 <= MAX_PIXELS);
    assert_eq!(render::max_scale(1 << 13, 1 << 12), 1);
    assert_eq!(render::max_scale(1 << 14, 1 << 13), 0);
}

#[test]
fn unchecked_worlds_do_not_panic() {
    let map = small_map();
    let mut world = small_world();
    world.units.push(Unit::new(7, i32::MAX - 1, i32::MIN, i32::MAX, i32::MAX, UnitType::Hall));
    world.units.push(Unit::new(8, 2, 2, 0, -4, UnitType::Other));
    world.units.push(Unit::new(9, -100, -100, 120, 3, UnitType::Other));
    world.doors.push(Door { id: 2, units: [1, 99], x0: 0, y0: 0, x1: 5, y1: 5, opening: false });
    world.doors.push(Door { id: 3, units: [1, 2], x0: i32::MIN, y0: 3, x1: i32::MAX, y1: 3, opening: false });
    world.object_cells.extend([[i32::MIN, i32::MAX], [-1, -1], [16, 12]]);
    let options = RenderOptions { scale: 2, labels: true, legend: true };
    for frame in [
        world.frame,
        Frame { angle: 0.4, ..world.frame },
        Frame { angle: f64::NAN, ..world.frame },
        Frame { angle: f64::INFINITY, ..world.frame },
        Frame { angle: 1e300, world_size: [u32::MAX, 1], map_size: [1, u32::MAX] },
        Frame { angle: 0.0, world_size: [0, 0], map_size: [0, 0] },
    ] {
        let w = World { frame, ..world.clone() };
        let p = render(&map, Some(&w), &options);
        assert_eq!((p.width(), p.height()), (32, 24));
    }
    // What lies on the map is still drawn: door 3 runs across all of row 3; door 2 is the
    // rectangle of cells (0, 0) to (5, 5) (doors are rectangles through thick walls).
    let p = render(&map, Some(&world), &no_labels(1));
    assert_eq!(rgb(&p, 0, 3), CYAN);
    assert_eq!(rgb(&p, 15, 3), CYAN);
    assert_eq!(rgb(&p, 0, 0), CYAN);
    assert_eq!(rgb(&p, 5, 5), CYAN);
}

#[test]
fn every_dataset_map_renders_with_its_cell_counts() {
    let Some(datasets) = crate::common::datasets("every_dataset_map_renders_with_its_cell_counts") else { return };
    let dir = datasets.join("bormann2016");
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "png"))
        .collect();
    paths.sort();
    assert!(paths.len() >= 10, "found only {} maps in {}", paths.len(), dir.display());
    paths.push(datasets.join("radish/ubremen-cartesium.png"));

    // Two threads: the maps are independent and the machine has two cores.
    let (left, right) = paths.split_at(paths.len() / 2);
    std::thread::scope(|s| {
        let a = s.spawn(|| left.iter().for_each(|p| check_dataset_map(p)));
        let b = s.spawn(|| right.iter().for_each(|p| check_dataset_map(p)));
        a.join().expect("first half");
        b.join().expect("second half");
    });
}

/// The same check on a synthetic map (PGM) and a drawn gray+alpha PNG.
#[test]
fn generated_maps_render_with_their_cell_counts() {
    let dir = std::env::temp_dir().join(format!("ksmcmc-render-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let synth = ksmcmc::floorplan::synth::generate(&Default::default(), 5).expect("synth");
    let pgm = dir.join("synth.pgm");
    std::fs::write(&pgm, synth.map_pgm()).expect("write");
    check_dataset_map(&pgm);
    let (w, h) = (50u32, 40u32);
    let mut data = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let gray = if x < 5 || y < 5 {
                205
            } else if x == 5 || y == 5 || x == 45 || y == 35 {
                0
            } else {
                255
            };
            data.extend([gray, 255u8]);
        }
    }
    let mut bytes = Vec::new();
    let mut enc = png::Encoder::new(&mut bytes, w, h);
    enc.set_color(png::ColorType::GrayscaleAlpha);
    enc.set_depth(png::BitDepth::Eight);
    enc.write_header().expect("header").write_image_data(&data).expect("data");
    let gray_alpha = dir.join("gray_alpha.png");
    std::fs::write(&gray_alpha, bytes).expect("write");
    check_dataset_map(&gray_alpha);
}

fn check_dataset_map(path: &std::path::Path) {
    let map = OccupancyMap::load(path, &Default::default()).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let pixmap = draw_map(map.classified());
    assert_eq!((pixmap.width() as usize, pixmap.height() as usize), (map.width(), map.height()), "{}", path.display());
    let mut counts = [0usize; 3];
    for p in pixmap.pixels() {
        let c = p.demultiply();
        let c = [c.red(), c.green(), c.blue()];
        let class = [Cell::Free, Cell::Unknown, Cell::Occupied].iter().position(|&k| cell_rgb(k) == c);
        let class = class.unwrap_or_else(|| panic!("{}: pixel colour {c:?} is no class", path.display()));
        counts[class] += 1;
    }
    assert_eq!(
        counts,
        [map.count(Cell::Free), map.count(Cell::Unknown), map.count(Cell::Occupied)],
        "{}",
        path.display()
    );
    assert!(counts[0] > 0 && counts[2] > 0, "{}: a real map has free and occupied cells", path.display());
}

#[test]
fn walls_doors_and_labels_draw_over_the_fill() {
    let map = Grid::new(16, 12, Cell::Free);
    let pixmap = render(&map, Some(&small_world()), &no_labels(2));
    // The shared wall at column 8 is blue on both sides' tints, the door cyan over it.
    assert_eq!(rgb(&pixmap, 2 * 8, 2 * 2), BLUE);
    assert_eq!(rgb(&pixmap, 2 * 8 + 1, 2 * 4), CYAN);
    assert_eq!(rgb(&pixmap, 2 * 7, 2 * 4), room_fill_rgb(UnitType::Room));
    assert_eq!(rgb(&pixmap, 2 * 9, 2 * 4), room_fill_rgb(UnitType::Corridor));
    // Each type keeps its own tint, and the tints differ from each other and from white.
    let tints: Vec<[u8; 3]> = UnitType::ALL.iter().map(|&k| room_fill_rgb(k)).collect();
    for (i, a) in tints.iter().enumerate() {
        assert_ne!(*a, WHITE);
        for b in &tints[i + 1..] {
            let d: i32 = a.iter().zip(b).map(|(x, y)| (*x as i32 - *y as i32).abs()).sum();
            assert!(d >= 30, "tints {a:?} and {b:?} look alike");
        }
    }
}

#[test]
fn the_legend_lists_the_colours_drawn_in_the_emptiest_corner() {
    let map = Grid::new(120, 80, Cell::Free);
    let mut world = World::empty(120, 80);
    world.units.push(Unit::new(1, 2, 2, 40, 30, UnitType::Room));
    world.units.push(Unit::new(2, 41, 2, 77, 30, UnitType::Corridor));
    world.units.push(Unit::new(3, 2, 45, 38, 33, UnitType::Hall));
    world.doors.push(Door { id: 1, units: [1, 2], x0: 41, y0: 10, x1: 41, y1: 14, opening: false });
    let entries = render::legend_entries(&world);
    let names: Vec<&str> = entries.iter().map(|e| e.0).collect();
    assert_eq!(names, ["room", "corridor", "hall", "wall", "door"]);
    let with = render(&map, Some(&world), &RenderOptions { scale: 2, labels: false, legend: true });
    let without = render(&map, Some(&world), &no_labels(2));
    // Everything that changed lies in one box in the bottom right (the other corners are
    // taken by units).
    let changed: Vec<(u32, u32)> = (0..with.height())
        .flat_map(|y| (0..with.width()).map(move |x| (x, y)))
        .filter(|&(x, y)| rgb(&with, x, y) != rgb(&without, x, y))
        .collect();
    assert!(changed.len() > 500, "the legend draws: {} pixels", changed.len());
    let xs = changed.iter().map(|c| c.0);
    let ys = changed.iter().map(|c| c.1);
    let (min_x, max_x) = (xs.clone().min().unwrap(), xs.max().unwrap());
    let (min_y, max_y) = (ys.clone().min().unwrap(), ys.max().unwrap());
    assert!(min_x > with.width() / 3 && min_y > with.height() / 3, "bottom right: from ({min_x}, {min_y})");
    assert!(max_x + 8 >= with.width() && max_y + 8 >= with.height(), "in the corner: to ({max_x}, {max_y})");
    // Its swatches show the tints and the wall colour.
    let shows = |c: [u8; 3]| changed.iter().any(|&(x, y)| rgb(&with, x, y) == c);
    assert!(shows(room_fill_rgb(UnitType::Room)) && shows(room_fill_rgb(UnitType::Corridor)) && shows(BLUE));
    assert!(shows(CYAN));
    // A picture too small for it goes without.
    let tiny = render(&Grid::new(20, 12, Cell::Free), Some(&small_world()), &RenderOptions::default());
    let bare = render(&Grid::new(20, 12, Cell::Free), Some(&small_world()), &no_labels(1));
    assert_eq!(tiny.data(), bare.data());
}

/// Labels on real, crowded maps: a chain run briefly on the Cartesium and two Bormann maps,
/// rendered with rooms and with units only, places no two labels on top of each other, every
/// label inside the picture, and none under the legend.
#[test]
fn labels_on_real_maps_never_overlap() {
    let Some(datasets) = crate::common::datasets("labels_on_real_maps_never_overlap") else { return };
    let maps = ["radish/ubremen-cartesium.png", "bormann2016/office_e.png", "bormann2016/lab_a_scan.png"];
    std::thread::scope(|s| {
        for name in maps {
            let path = datasets.join(name);
            s.spawn(move || check_labels_on(&path));
        }
    });
}

fn check_labels_on(path: &std::path::Path) {
    use ksmcmc::floorplan::{rooms::RoomConfig, Chain, ChainConfig};
    let map = OccupancyMap::load(path, &Default::default()).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut chain = Chain::new(&map, ChainConfig::default(), 7).expect("chain");
    chain.step(3000);
    let (with_rooms, _) = chain.best_world_with_rooms(&RoomConfig::default()).unwrap();
    let units_only = World { rooms: Vec::new(), ..with_rooms.clone() };
    assert!(with_rooms.units.len() >= 5, "{}: {} units", path.display(), with_rooms.units.len());
    for (world, what) in [(&with_rooms, "rooms"), (&units_only, "units")] {
        for scale in [1, 2, 4] {
            let options = RenderOptions { scale, labels: true, legend: true };
            let mut pixmap = render(map.classified(), None, &options);
            let placed = render::draw_world(&mut pixmap, map.width(), map.height(), world, &options);
            let at = format!("{} ({what}, scale {scale})", path.display());
            assert!(!placed.is_empty(), "{at}: some label fits");
            for (i, a) in placed.iter().enumerate() {
                assert!(a.left >= 0 && a.top >= 0, "{at}: {a:?}");
                assert!(a.left + a.width <= pixmap.width() as i64 && a.top + a.height <= pixmap.height() as i64);
                for b in &placed[i + 1..] {
                    assert!(!a.intersects(b), "{at}: {a:?} overlaps {b:?}");
                }
            }
            // Same world, same pixels.
            let again = render(map.classified(), Some(world), &options);
            assert_eq!(again.data(), pixmap.data(), "{at}: deterministic");
        }
    }
}

/// A unit with an angle of its own (issue 13) is drawn in the frame that angle gives: exactly
/// as the same unit in a world whose frame is that one, and beside an upright unit of the
/// world frame, which stays where it was.
#[test]
fn a_unit_at_its_own_angle_is_drawn_in_its_own_frame() {
    let map = Grid::new(120, 90, Cell::Free);
    let angle = 0.5;
    let turned = Frame::turned(120, 90, angle);
    let unit = Unit::new(1, 50, 40, 30, 20, UnitType::Room);
    let mut in_turned_frame = World::empty(120, 90);
    in_turned_frame.frame = turned;
    in_turned_frame.units.push(unit);
    let mut with_angle = World::empty(120, 90);
    with_angle.units.push(Unit { angle: Some(angle), ..unit });
    with_angle.validate().unwrap();
    assert_eq!(with_angle.unit_frame(&with_angle.units[0]), turned);
    for options in [no_labels(2), RenderOptions { scale: 2, labels: true, legend: true }] {
        let a = render(&map, Some(&in_turned_frame), &options);
        let b = render(&map, Some(&with_angle), &options);
        assert!(a.data() == b.data(), "the turned unit is drawn differently ({options:?})");
    }
    // With an upright unit beside it, both are drawn, each in its frame.
    let upright = Unit::new(2, 2, 2, 20, 15, UnitType::Corridor);
    with_angle.units.push(upright);
    let mut alone = World::empty(120, 90);
    alone.units.push(upright);
    let both = render(&map, Some(&with_angle), &no_labels(1));
    let only_upright = render(&map, Some(&alone), &no_labels(1));
    let only_turned = render(&map, Some(&in_turned_frame), &no_labels(1));
    for (x, y) in [(2, 2), (21, 16), (10, 2)] {
        assert_eq!(rgb(&both, x, y), BLUE, "upright wall at ({x},{y})");
        assert_eq!(rgb(&both, x, y), rgb(&only_upright, x, y));
    }
    let turned_wall = (0..120 * 90).find(|&i| rgb(&only_turned, i % 120, i / 120) == BLUE).unwrap();
    assert_eq!(rgb(&both, turned_wall % 120, turned_wall / 120), BLUE);
}
