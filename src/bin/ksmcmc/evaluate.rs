//! `ksmcmc evaluate`: quality on real and synthetic maps, for BENCHMARKS.md.

use crate::args::{self, CliError};
use crate::score::truth_regions;
use ksmcmc::floorplan::metrics::{prediction_rate, score_segmentation, SegmentationScore};
use ksmcmc::floorplan::rooms::RoomConfig;
use ksmcmc::floorplan::synth::{generate, SynthConfig};
use ksmcmc::floorplan::topology::{score_links, LinkScore};
use ksmcmc::floorplan::{Chain, ChainConfig, UnitType};
use ksmcmc::grid::{Cell, Classifier, Grid, OccupancyMap, Raster};
use std::ffi::OsString;
use std::path::{Path, PathBuf};

const HELP: &str = "\
Usage: ksmcmc evaluate [--datasets DIR] [--iterations N] [--seeds K] [--config FILE] [--only SET]
                       [--room-rules FILE] [--room-config FILE] [--learn FILE] [--cases FILE]
                       [--synth-from SEED]

Prints the quality tables of BENCHMARKS.md:
  bormann    room-segmentation precision and recall on the Bormann et al. maps in DIR/bormann2016
             (plain and furnished), scored as the benchmark does (see `ksmcmc score`)
  synthetic  K(W,M), precision and recall against the truth of K generated maps per kind
  wings      one chain against a chain per wing (floorplan::wings): K(W,M), the units'
             angles and the time on the two-wing kinds and every Bormann map
  cartesium  K(W,M) on DIR/radish/ubremen-cartesium.png over K seeds, and per seed the rooms
             and their types
  knowledge  weak prior versus knowledge supervision (Fig. 3.34): K(W,M), unit-count error,
             defects (adjacent room pairs whose connecting walls differ by over 10 %) and
             type accuracy against the synthetic truth
  paired     knowledge supervision minus the weak prior on the same maps and chain seeds,
             per synthetic kind: the mean difference of K(W,M) with its standard error
  paired-bormann  the bormann table in both modes, map by map, with the sums compared
  bormann-seeds   the bormann figures over chain seeds 1..=K: per map and for the means, the
             mean and standard deviation over seeds (how far one seed's table can be trusted)
  rooms      the room layer against synthetic truth, both modes: rooms per truth unit and
             type accuracy (the room covering most of each truth unit has the unit's type),
             on hall, two-corridor, cluttered, rotated and many-storage floors (seeds from
             --synth-from, default 300: the test floors; 310 - 321 choose evidence)
  scale      the bormann maps resampled to 0.025, 0.05 and 0.10 m a cell (the darkest cell of
             each 2x2 block; each cell repeated 2x2), read as a map.yaml of that resolution,
             explained as `ksmcmc floorplan` does, labels taken back and scored; with the time
  doors      doors the chain found whose two units the room layer put in one room, as
             `ksmcmc floorplan` (wings and all) finds them at seed 1: openings (a passage of
             1.2 m or more within the room) and the rest (rooms merged across a door), on the
             bormann maps, Cartesium and the generated rooms kinds
  format     each bormann map and Cartesium as a 16-bit PNG, a PGM and a PGM with a map.yaml
             (0.05 m, map_server's usual thresholds) of the same pixels (transparent ones
             written as map_saver's unknown gray): whether the cells and the labels of
             `ksmcmc floorplan` at seed 1 are the same from all three
  loo        leave-one-floor-out over the ten bormann floors for the room layer's lengths
             set with these floors in view (min_wall_len_m, max_wall_gap_m, door_half_width_m,
             three values each): per floor, the settings that score best on the other nine and
             the held-out floor's figures under them, beside its figures under the defaults
  routes     route length over the shortest free path (floorplan::route::study) between
             200 pairs of free cells in different rooms per floor, on the explained floors
             of the rooms set's kinds
  frontier   placeholders (floorplan::frontier) on generated floors of six kinds explored in
             part by the simulated robot (30, 55 and 80 % of the free space seen): AUC and
             Brier score of P(NewRoom), type accuracy and log loss against what truly lies
             behind, and the doors of unentered rooms with a placeholder (P >= 0.5) within
             1.5 m; weights learned on seeds 4001-4036, scored on 4101-4103, beside the
             hand-set and built-in rules. --learn FILE writes the learned rules, --cases
             FILE every placeholder's measures and what lies behind it (CSV)
  goals      metres the simulated robot drives to find a new hall (generated floors with
             one and two halls) or any new room (four kinds), following the nearest
             frontier and driving to the placeholder with the most probability of the goal
             per metre, from three starts on each of the frontier set's test floors
  settle     candidate settle rules (floorplan::settled) watching one chain per map to 150,000
             iterations: where each stops and the plan there against the plan at 20,000, on
             K generated floors per kind (where the rule is chosen) and the bormann floors
  realistic  the room layer on generated floors drawn like real maps (open arches between
             hall and corridors, glass panes with rays fanning out, furniture along walls,
             wall gaps, rooms never entered) at 0.025, 0.05 and 0.10 m and rotated, K seeds
             from --synth-from (default 500: held out from every choice; 600 on are the
             floors to look at): segmentation, door links, doors in one room, room types
             and time, as `ksmcmc floorplan` at seed 1
bormann also scores door topology: a truth link is a drawn doorway line on free map cells
between two truth rooms; a predicted link is two segments, standing for the truth rooms they
overlap most, touching along at least 10 free cells (see floorplan::topology).
DIR defaults to ../shared/datasets, N to 20000 iterations, K to 6. --only runs one set.
--room-rules FILE: the room rules of knowledge mode (default: the built-in ones).
--also-room-rules FILE (repeatable): bormann-seeds in knowledge mode also scores these room
rules on the same chains, one more table each.
--room-config FILE: the room layer's settings (floorplan::rooms::RoomConfig as JSON, for
example {\"max_wall_gap_m\": 0}, lengths in metres; default: the built-in ones).
--also-room-config FILE (repeatable): bormann-seeds also scores these room-layer settings on
the same chains, in either mode, one more table each.
";

/// The sets `--only` can name.
const SETS: [&str; 18] = [
    "cartesium",
    "synthetic",
    "bormann",
    "knowledge",
    "paired",
    "paired-bormann",
    "bormann-seeds",
    "rooms",
    "routes",
    "wings",
    "scale",
    "doors",
    "format",
    "loo",
    "frontier",
    "goals",
    "settle",
    "realistic",
];

struct Opts {
    iterations: u64,
    seeds: u64,
    config: ChainConfig,
    /// Further room rules bormann-seeds scores on the same knowledge-mode chains: (file, text).
    more_rules: Vec<(String, String)>,
    /// The room layer's settings.
    rooms: RoomConfig,
    /// Further room-layer settings bormann-seeds scores on the same chains: (file, settings).
    more_rooms: Vec<(String, RoomConfig)>,
    /// Where `frontier` writes the frontier rules it learns.
    learn: Option<PathBuf>,
    /// Where `frontier` writes its placeholders' measures and truth (CSV).
    cases: Option<PathBuf>,
    /// The first generated floor's seed of the `rooms` set (300: the test floors; 310 - 321
    /// were kept aside to choose the rules' evidence on) and of the `realistic` set (500: held
    /// out; 600 on for looking at failures), when given.
    synth_from: Option<u64>,
}

impl Opts {
    /// The `rooms` set's first seed: 300 unless given.
    fn rooms_from(&self) -> u64 {
        self.synth_from.unwrap_or(300)
    }

    /// The same options with knowledge supervision switched on or off.
    fn with_knowledge(&self, enabled: bool) -> Opts {
        let mut config = self.config.clone();
        config.knowledge.enabled = enabled;
        Opts {
            config,
            more_rules: self.more_rules.clone(),
            more_rooms: self.more_rooms.clone(),
            learn: self.learn.clone(),
            cases: self.cases.clone(),
            ..*self
        }
    }
}

fn explain(map: &OccupancyMap, o: &Opts, seed: u64) -> Result<Chain, CliError> {
    let mut chain = Chain::new(map, o.config.clone(), seed).map_err(|e| CliError::Failed(e.to_string()))?;
    chain.step(o.iterations);
    Ok(chain)
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

/// Segmentation and door-topology scores of one map.
#[derive(Clone, Copy)]
struct MapScore {
    seg: SegmentationScore,
    links: LinkScore,
}

impl MapScore {
    fn figures(&self) -> [f64; 4] {
        [self.seg.precision, self.seg.recall, self.links.precision, self.links.recall]
    }
}

/// The Bormann maps in `dir`: names that have a `_gt_segmentation.png`.
fn bormann_names(dir: &Path) -> Result<Vec<String>, CliError> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .map_err(|e| args::failed(dir.display(), e))?
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter_map(|n| n.strip_suffix("_gt_segmentation.png").map(str::to_string))
        .collect();
    names.sort();
    Ok(names)
}

/// Scores of map `name` (plain, then furnished) with the room layer of the options' mode,
/// chain seed 1.
fn bormann_map(dir: &Path, name: &str, o: &Opts) -> Result<[MapScore; 2], CliError> {
    bormann_map_seed(dir, name, o, 1)
}

/// [`bormann_map`] with chain seed `seed`.
fn bormann_map_seed(dir: &Path, name: &str, o: &Opts, seed: u64) -> Result<[MapScore; 2], CliError> {
    Ok(bormann_map_variants(dir, name, o, seed)?[0])
}

/// The room rules and room-layer settings bormann-seeds scores on the same chains: the
/// options' own, then (in knowledge mode) each of `o.more_rules`, then each of `o.more_rooms`.
fn room_variants(o: &Opts) -> Vec<(Option<String>, RoomConfig)> {
    let own = o.config.knowledge.room_kb.clone();
    std::iter::once((own.clone(), o.rooms))
        .chain(o.more_rules.iter().filter(|_| o.config.knowledge.enabled).map(|(_, t)| (Some(t.clone()), o.rooms)))
        .chain(o.more_rooms.iter().map(|(_, c)| (own.clone(), *c)))
        .collect()
}

/// The scores of map `name` with chain seed `seed`, for each of [`room_variants`] on the same
/// chains.
fn bormann_map_variants(dir: &Path, name: &str, o: &Opts, seed: u64) -> Result<Vec<[MapScore; 2]>, CliError> {
    use ksmcmc::floorplan::export::RoomInput;
    let truth = truth_regions(&dir.join(format!("{name}_gt_segmentation.png")))?;
    let rules = room_variants(o);
    let mut out: Vec<Vec<MapScore>> = vec![Vec::new(); rules.len()];
    for suffix in ["", "_furnitures"] {
        let path = dir.join(format!("{name}{suffix}.png"));
        let mut map = args::load_map(&path)?;
        map.set_classifier(Classifier::auto()).map_err(|e| args::failed("classifier", e))?;
        let mut chain = explain(&map, o, seed)?;
        let input = RoomInput::of(&mut chain);
        let free = map.classified().map(|&c| c == Cell::Free);
        for (v, (r, rooms)) in rules.iter().enumerate() {
            let labels = floorplan_labels(&map, input.clone().with_room_rules(r.clone()), rooms)?;
            out[v].push(MapScore {
                seg: score_segmentation(&labels, &truth),
                links: score_links(&labels, &truth, &free),
            });
        }
    }
    Ok(out.into_iter().map(|v| [v[0], v[1]]).collect())
}

/// The room labels `ksmcmc floorplan` writes for `map` from the chain's `input`: by the
/// walls where no wall direction holds most of the building (floorplan::wings).
fn floorplan_labels(
    map: &OccupancyMap,
    input: ksmcmc::floorplan::export::RoomInput,
    rooms: &RoomConfig,
) -> Result<Grid<u32>, CliError> {
    use ksmcmc::floorplan::wings::{WingConfig, WingLayout};
    let (world, labels) = input.clone().explain(rooms).map_err(rooms_failed)?;
    let layout = WingLayout::find(map, &labels, world.frame.angle, &WingConfig::default());
    let labels = match layout.as_ref().and_then(WingLayout::by_walls) {
        Some(angles) => input.by_walls(angles).explain(rooms).map_err(rooms_failed)?.1,
        None => labels,
    };
    Ok(labels.map(|&l| l as u32))
}

/// The room layer's failure, as the command's error.
fn rooms_failed(e: ksmcmc::floorplan::rooms::RoomError) -> CliError {
    args::failed("finding the rooms", e)
}

/// The cell sizes `scale` reads each benchmark floor at, metres, and how many cells of the
/// 0.05 m original each cell spans along a side (0.5: each original cell is 2 x 2 cells).
const SCALES: [(f64, f64); 3] = [(0.025, 0.5), (0.05, 1.0), (0.10, 2.0)];

/// `raster` at `factor` times its cell size: 2 keeps the darkest opaque pixel of each 2 x 2
/// block (a wall one cell thick survives, as a coarser SLAM map would draw it), 0.5 repeats
/// each pixel 2 x 2, 1 is the raster itself.
fn resample(raster: &Raster, factor: f64) -> Raster {
    let (w, h) = (raster.width(), raster.height());
    let opaque = |x: usize, y: usize| raster.alpha.as_ref().is_none_or(|a| *a.at(x, y) >= 32768);
    if factor > 1.0 {
        let (cw, ch) = (w.div_ceil(2), h.div_ceil(2));
        let mut gray = Vec::with_capacity(cw * ch);
        let mut alpha = Vec::with_capacity(cw * ch);
        for y in 0..ch {
            for x in 0..cw {
                let block =
                    (2 * y..(2 * y + 2).min(h)).flat_map(|yy| (2 * x..(2 * x + 2).min(w)).map(move |xx| (xx, yy)));
                let dark = block.filter(|&(xx, yy)| opaque(xx, yy)).map(|(xx, yy)| *raster.gray.at(xx, yy)).min();
                gray.push(dark.unwrap_or(u16::MAX));
                alpha.push(if dark.is_some() { u16::MAX } else { 0 });
            }
        }
        let alpha = raster.alpha.as_ref().map(|_| Grid::from_vec(cw, ch, alpha).expect("size"));
        return Raster { gray: Grid::from_vec(cw, ch, gray).expect("size"), alpha };
    }
    if factor < 1.0 {
        let up = |g: &Grid<u16>| {
            let cells = (0..2 * h).flat_map(|y| (0..2 * w).map(move |x| *g.at(x / 2, y / 2))).collect();
            Grid::from_vec(2 * w, 2 * h, cells).expect("size")
        };
        return Raster { gray: up(&raster.gray), alpha: raster.alpha.as_ref().map(up) };
    }
    raster.clone()
}

/// Labels found on a map `factor` times coarser, back on the original grid of `free` cells:
/// each original cell takes the label of the resampled cell it lies in (at its top-left corner,
/// on a finer map). On a coarser map a wall cell also covers the free cells beside the wall
/// (a 2 x 2 block is a wall if any of its cells is): a free original cell in such a block
/// takes the label of the coarse cell it faces across the block's edge, as the room it lies in,
/// so that the score does not count the resampling's thicker walls as floor left unlabelled
/// (`fill`; without it such cells stay 0).
fn labels_back(labels: &Grid<u32>, factor: f64, free: &Grid<bool>, fill: bool) -> Grid<u32> {
    let (w, h) = (free.width(), free.height());
    let get = |x: i64, y: i64| labels.get(x, y).copied().unwrap_or(0);
    let at = |x: usize, y: usize| {
        if factor < 1.0 {
            return get(2 * x as i64, 2 * y as i64);
        }
        if factor == 1.0 {
            return get(x as i64, y as i64);
        }
        let (cx, cy) = ((x / 2) as i64, (y / 2) as i64);
        let own = get(cx, cy);
        if own != 0 || !fill || !*free.at(x, y) {
            return own;
        }
        let (sx, sy) = (if x % 2 == 0 { -1 } else { 1 }, if y % 2 == 0 { -1 } else { 1 });
        [(cx + sx, cy), (cx, cy + sy), (cx + sx, cy + sy)]
            .iter()
            .map(|&(a, b)| get(a, b))
            .find(|&l| l != 0)
            .unwrap_or(0)
    };
    Grid::from_vec(w, h, (0..h).flat_map(|y| (0..w).map(move |x| at(x, y))).collect()).expect("size")
}

/// The benchmark floors read at other cell sizes (issue 31): each floor resampled as
/// [`resample`] does, given as a map.yaml of that resolution would give it (one rule,
/// `Classifier::for_map`), explained as `ksmcmc floorplan` does at seed 1, its labels taken
/// back to the original grid and scored against the truth; with the run's wall time, and the
/// segmentation scores without [`labels_back`]'s filling of the thicker walls.
fn scale(dir: &Path, o: &Opts) -> Result<(), CliError> {
    use ksmcmc::floorplan::export::RoomInput;
    use ksmcmc::grid::MapYaml;
    let dir = dir.join("bormann2016");
    let names = bormann_names(&dir)?;
    println!("\n### The benchmark floors at other resolutions ({} iterations, seed 1)\n", o.iterations);
    println!("| map | m per cell | precision | recall | link precision | link recall | seconds | precision, walls not filled | recall, walls not filled |");
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut sums = [[0.0; 7]; SCALES.len()];
    let mut n = 0.0f64;
    for name in &names {
        let truth = truth_regions(&dir.join(format!("{name}_gt_segmentation.png")))?;
        for suffix in ["", "_furnitures"] {
            n += 1.0;
            let path = dir.join(format!("{name}{suffix}.png"));
            let original = args::load_classified(&path, "auto")?;
            let free = original.classified().map(|&c| c == Cell::Free);
            for (k, &(resolution, factor)) in SCALES.iter().enumerate() {
                let yaml = MapYaml { resolution, ..MapYaml::for_image("map.pgm") };
                let map = OccupancyMap::from_raster(
                    resample(original.raster(), factor),
                    yaml.clone(),
                    Classifier::for_map(&yaml),
                );
                let t0 = std::time::Instant::now();
                let mut chain = explain(&map, o, 1)?;
                let labels = floorplan_labels(&map, RoomInput::of(&mut chain), &o.rooms)?;
                let seconds = t0.elapsed().as_secs_f64();
                let naive = score_segmentation(&labels_back(&labels, factor, &free, false), &truth);
                let labels = labels_back(&labels, factor, &free, true);
                let s =
                    MapScore { seg: score_segmentation(&labels, &truth), links: score_links(&labels, &truth, &free) };
                let f = s.figures();
                let row = [f[0], f[1], f[2], f[3], seconds, naive.precision, naive.recall];
                for (a, b) in sums[k].iter_mut().zip(row) {
                    *a += b;
                }
                println!(
                    "| {name}{suffix} | {resolution} | {} | {seconds:.2} | {:.3} | {:.3} |",
                    fmt4(f),
                    naive.precision,
                    naive.recall
                );
            }
        }
    }
    for (k, &(resolution, _)) in SCALES.iter().enumerate() {
        let m = sums[k].map(|v| v / n.max(1.0));
        println!(
            "| **mean** | {resolution} | {} | {:.2} | {:.3} | {:.3} |",
            fmt4([m[0], m[1], m[2], m[3]]),
            m[4],
            m[5],
            m[6]
        );
    }
    Ok(())
}

/// Doors within one room (floorplan::rooms::doors_in_one_room) on the maps in `dir` and generated floors, as
/// `ksmcmc floorplan` explains them (a chain per wing where the walls follow several
/// directions), chain seed 1.
fn doors(dir: &Path, o: &Opts) -> Result<(), CliError> {
    use ksmcmc::floorplan::rooms::doors_in_one_room;
    use ksmcmc::floorplan::wings::{WingConfig, Wings};
    let mut maps: Vec<(String, OccupancyMap)> = Vec::new();
    let bormann = dir.join("bormann2016");
    for name in bormann_names(&bormann)? {
        for suffix in ["", "_furnitures"] {
            maps.push((
                format!("{name}{suffix}"),
                args::load_classified(&bormann.join(format!("{name}{suffix}.png")), "auto")?,
            ));
        }
    }
    maps.push(("Cartesium".into(), args::load_classified(&dir.join("radish/ubremen-cartesium.png"), "auto")?));
    for (kind, config) in room_kinds() {
        for seed in 300..302u64 {
            maps.push((format!("{kind} {seed}"), generate(&config, seed).map_err(|e| args::failed(kind, e))?.map));
        }
    }
    println!("\n### Doors within one room ({} iterations, seed 1, as `ksmcmc floorplan`)\n", o.iterations);
    println!("| map | doors | openings | doors in one room | share of the doors that are no opening |");
    println!("|---|---|---|---|---|");
    let mut worst: f64 = 0.0;
    for (name, map) in &maps {
        let wings = Wings::run(map, &o.config, &WingConfig::default(), 1, o.iterations, &o.rooms)
            .map_err(|e| args::failed(name, e))?;
        let w = &wings.world;
        let openings = w.doors.iter().filter(|d| d.opening).count();
        let inside = doors_in_one_room(w);
        let share = inside as f64 / (w.doors.len() - openings).max(1) as f64;
        worst = worst.max(share);
        println!("| {name} | {} | {openings} | {inside} | {share:.2} |", w.doors.len());
    }
    println!("| **worst** | | | | {worst:.2} |");
    Ok(())
}

/// The same pixels as a PNG, a PGM and a map.yaml (issue 31): the three files of `raster`
/// (16-bit gray, transparent pixels as 205 of 255, map_saver's unknown).
fn three_formats(raster: &Raster) -> Result<[OccupancyMap; 3], CliError> {
    use ksmcmc::grid::Limits;
    let (w, h) = (raster.width(), raster.height());
    let opaque = |i: usize| raster.alpha.as_ref().is_none_or(|a| a.cells()[i] >= 32768);
    let gray: Vec<u16> =
        raster.gray.cells().iter().enumerate().map(|(i, &g)| if opaque(i) { g } else { 205 * 257 }).collect();
    let be: Vec<u8> = gray.iter().flat_map(|g| g.to_be_bytes()).collect();
    let mut pgm = format!("P5\n{w} {h}\n65535\n").into_bytes();
    pgm.extend_from_slice(&be);
    let mut png_bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut png_bytes, w as u32, h as u32);
        enc.set_color(png::ColorType::Grayscale);
        enc.set_depth(png::BitDepth::Sixteen);
        let mut writer = enc.write_header().map_err(|e| args::failed("PNG", e))?;
        writer.write_image_data(&be).map_err(|e| args::failed("PNG", e))?;
    }
    let yaml = "image: map.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
    let limits = Limits::default();
    let read = |map: Result<OccupancyMap, ksmcmc::grid::MapError>| -> Result<OccupancyMap, CliError> {
        let mut map = map.map_err(|e| args::failed("map", e))?;
        let rule = Classifier::for_map(map.yaml());
        map.set_classifier(rule).map_err(|e| args::failed("map", e))?;
        Ok(map)
    };
    Ok([
        read(OccupancyMap::from_image_bytes(&png_bytes, Classifier::default(), &limits))?,
        read(OccupancyMap::from_image_bytes(&pgm, Classifier::default(), &limits))?,
        read(OccupancyMap::from_yaml_and_image(yaml, &pgm, &limits))?,
    ])
}

/// Whether the same pixels give the same cells and rooms from a PNG, a PGM and a map.yaml.
fn format(dir: &Path, o: &Opts) -> Result<(), CliError> {
    use ksmcmc::floorplan::export::RoomInput;
    let bormann = dir.join("bormann2016");
    let mut paths: Vec<(String, PathBuf)> = Vec::new();
    for name in bormann_names(&bormann)? {
        for suffix in ["", "_furnitures"] {
            paths.push((format!("{name}{suffix}"), bormann.join(format!("{name}{suffix}.png"))));
        }
    }
    paths.push(("Cartesium".into(), dir.join("radish/ubremen-cartesium.png")));
    println!("\n### The same pixels as PNG, PGM and map.yaml ({} iterations, seed 1)\n", o.iterations);
    println!("| map | cells the same | labels the same | rooms |");
    println!("|---|---|---|---|");
    let mut same = 0;
    for (name, path) in &paths {
        let maps = three_formats(args::load_map(path)?.raster())?;
        let cells = maps.iter().all(|m| m.classified() == maps[0].classified());
        let mut labels = Vec::new();
        for map in &maps {
            let mut chain = explain(map, o, 1)?;
            labels.push(floorplan_labels(map, RoomInput::of(&mut chain), &o.rooms)?);
        }
        let equal = labels.iter().all(|l| *l == labels[0]);
        same += equal as usize;
        let rooms = labels[0].cells().iter().copied().max().unwrap_or(0);
        println!("| {name} | {} | {} | {rooms} |", yes(cells), yes(equal));
    }
    println!("| **all** | | {same} of {} | |", paths.len());
    Ok(())
}

fn yes(b: bool) -> &'static str {
    if b {
        "yes"
    } else {
        "**no**"
    }
}

/// The room-layer settings `loo` chooses among: every combination of three values of the
/// three lengths that were set with the benchmark floors in view, the defaults first.
fn loo_grid(base: &RoomConfig) -> Vec<RoomConfig> {
    let mut grid = vec![*base];
    for wall in [1.5, 2.0, 2.5] {
        for gap in [2.0, 2.5, 3.0] {
            for door in [0.5, 0.6, 0.7] {
                let c = RoomConfig { min_wall_len_m: wall, max_wall_gap_m: gap, door_half_width_m: door, ..*base };
                if c != *base {
                    grid.push(c);
                }
            }
        }
    }
    grid
}

/// Leave-one-floor-out (issue 31): for each benchmark floor, the room-layer settings of
/// [`loo_grid`] whose mean of the eight figures (plain and furnished) is best on the other
/// floors, and the held-out floor's figures under them, beside the defaults' (in-sample).
fn loo(dir: &Path, o: &Opts) -> Result<(), CliError> {
    let bormann = dir.join("bormann2016");
    let names = bormann_names(&bormann)?;
    let grid = loo_grid(&o.rooms);
    let variants = Opts {
        more_rules: Vec::new(),
        more_rooms: grid[1..].iter().map(|c| (String::new(), *c)).collect(),
        ..o.with_knowledge(o.config.knowledge.enabled)
    };
    // scores[floor][variant]: the eight figures, plain then furnished.
    let mut scores: Vec<Vec<[f64; 8]>> = Vec::new();
    for name in &names {
        let per = bormann_map_variants(&bormann, name, &variants, 1)?;
        scores.push(
            per.iter()
                .map(|[p, f]| {
                    let (a, b) = (p.figures(), f.figures());
                    [a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]]
                })
                .collect(),
        );
    }
    let total = |f: &[f64; 8]| f.iter().sum::<f64>();
    println!(
        "\n### Leave-one-floor-out: the room layer's lengths ({} iterations, seed 1, {} settings)\n",
        o.iterations,
        grid.len()
    );
    println!("Each floor's figures under the defaults (in-sample: set with all ten floors in view) and under the settings that score best on the other nine (held out).\n");
    println!("| floor | chosen on the other nine (wall, gap, door half-width, m) | in-sample P / R / LP / LR (plain) | held-out (plain) | in-sample (furnished) | held-out (furnished) |");
    println!("|---|---|---|---|---|---|");
    let (mut ins, mut out) = ([0.0; 8], [0.0; 8]);
    for (f, name) in names.iter().enumerate() {
        let score_without = |v: usize| (0..names.len()).filter(|&g| g != f).map(|g| total(&scores[g][v])).sum::<f64>();
        let best = (0..grid.len()).fold(0, |b, v| if score_without(v) > score_without(b) + 1e-12 { v } else { b });
        let c = grid[best];
        let (a, h) = (scores[f][0], scores[f][best]);
        for k in 0..8 {
            ins[k] += a[k];
            out[k] += h[k];
        }
        let four = |x: &[f64; 8], i: usize| fmt4([x[i], x[i + 1], x[i + 2], x[i + 3]]).replace(" | ", " / ");
        println!(
            "| {name} | {}, {}, {} | {} | {} | {} | {} |",
            c.min_wall_len_m,
            c.max_wall_gap_m,
            c.door_half_width_m,
            four(&a, 0),
            four(&h, 0),
            four(&a, 4),
            four(&h, 4)
        );
    }
    let n = names.len().max(1) as f64;
    let (ins, out) = (ins.map(|v| v / n), out.map(|v| v / n));
    let four = |x: &[f64; 8], i: usize| fmt4([x[i], x[i + 1], x[i + 2], x[i + 3]]).replace(" | ", " / ");
    println!("| **mean** | | {} | {} | {} | {} |", four(&ins, 0), four(&out, 0), four(&ins, 4), four(&out, 4));
    Ok(())
}

fn fmt4(f: [f64; 4]) -> String {
    f.iter().map(|v| format!("{v:.3}")).collect::<Vec<_>>().join(" | ")
}

fn bormann(dir: &Path, o: &Opts) -> Result<(), CliError> {
    let dir = dir.join("bormann2016");
    let names = bormann_names(&dir)?;
    let mode = if o.config.knowledge.enabled { "knowledge" } else { "weak prior" };
    println!(
        "\n### Room segmentation and door topology, Bormann et al. maps ({} iterations, seed 1, {mode})\n",
        o.iterations
    );
    println!("| map | precision | recall | link precision | link recall | precision (furnished) | recall (furnished) | link precision (furnished) | link recall (furnished) |");
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut sums = [[0.0; 4]; 2];
    for name in &names {
        let scores = bormann_map(&dir, name, o)?;
        for (sum, s) in sums.iter_mut().zip(&scores) {
            for (a, b) in sum.iter_mut().zip(s.figures()) {
                *a += b;
            }
        }
        println!("| {name} | {} | {} |", fmt4(scores[0].figures()), fmt4(scores[1].figures()));
    }
    let n = names.len().max(1) as f64;
    let means = sums.map(|s| s.map(|v| v / n));
    println!("| **mean** | {} | {} |", fmt4(means[0]), fmt4(means[1]));
    Ok(())
}

/// Knowledge supervision against the weak prior on the Bormann maps, same chain seed: the
/// per-map difference of the eight figures and the sums the issue compares.
fn paired_bormann(dir: &Path, o: &Opts) -> Result<(), CliError> {
    let dir = dir.join("bormann2016");
    let names = bormann_names(&dir)?;
    println!("\n### Knowledge minus weak prior, Bormann et al. maps ({} iterations, seed 1)\n", o.iterations);
    println!("| map | mode | precision | recall | link precision | link recall | precision (furnished) | recall (furnished) | link precision (furnished) | link recall (furnished) |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let mut sums = [[[0.0; 4]; 2]; 2];
    for name in &names {
        for (m, enabled) in [true, false].into_iter().enumerate() {
            let scores = bormann_map(&dir, name, &o.with_knowledge(enabled))?;
            for (k, s) in scores.iter().enumerate() {
                for (a, b) in sums[m][k].iter_mut().zip(s.figures()) {
                    *a += b;
                }
            }
            let mode = if enabled { "knowledge" } else { "weak prior" };
            println!("| {name} | {mode} | {} | {} |", fmt4(scores[0].figures()), fmt4(scores[1].figures()));
        }
    }
    let n = names.len().max(1) as f64;
    let means = sums.map(|m| m.map(|s| s.map(|v| v / n)));
    for (mean, mode) in means.iter().zip(["knowledge", "weak prior"]) {
        println!("| **mean** | {mode} | {} | {} |", fmt4(mean[0]), fmt4(mean[1]));
    }
    println!();
    for (mean, mode) in means.iter().zip(["knowledge", "weak prior"]) {
        let seg: f64 = mean.iter().map(|f| f[0] + f[1]).sum();
        let links: f64 = mean.iter().map(|f| f[2] + f[3]).sum();
        println!("{mode}: sum of the four segmentation means {seg:.3}, of the four link means {links:.3}  ");
    }
    Ok(())
}

/// Mean and sample standard deviation.
fn mean_sd(v: &[f64]) -> (f64, f64) {
    let m = mean(v);
    let var = v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (v.len().max(2) - 1) as f64;
    (m, var.sqrt())
}

fn fmt_mean_sd(v: &[f64]) -> String {
    let (m, sd) = mean_sd(v);
    format!("{m:.3} ± {sd:.3}")
}

/// The eight Bormann figures of every map over chain seeds 1..=K: per map the mean ± standard
/// deviation over seeds, and for the floor means (taken per seed) the same. The seed-1 table
/// is one draw from these.
fn bormann_seeds(dir: &Path, o: &Opts) -> Result<(), CliError> {
    let dir = dir.join("bormann2016");
    let names = bormann_names(&dir)?;
    let mode = if o.config.knowledge.enabled { "knowledge" } else { "weak prior" };
    let mut variants = vec![match (&o.config.knowledge.room_kb, o.config.knowledge.enabled) {
        (_, false) => String::new(),
        (None, true) => ", built-in room rules".to_string(),
        (Some(_), true) => ", --room-rules".to_string(),
    }];
    if o.config.knowledge.enabled {
        variants.extend(o.more_rules.iter().map(|(f, _)| format!(", room rules {f}")));
    }
    variants.extend(o.more_rooms.iter().map(|(f, _)| format!(", room layer {f}")));
    // figures[variant][seed][map][8]
    let mut figures: Vec<Vec<Vec<[f64; 8]>>> = vec![vec![Vec::new(); o.seeds as usize]; variants.len()];
    let mut rows: Vec<Vec<String>> = vec![Vec::new(); variants.len()];
    for name in &names {
        for (k, seed) in (1..=o.seeds).enumerate() {
            for (v, s) in bormann_map_variants(&dir, name, o, seed)?.into_iter().enumerate() {
                let (a, b) = (s[0].figures(), s[1].figures());
                figures[v][k].push([a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]]);
            }
        }
        for (v, fig) in figures.iter().enumerate() {
            let m = fig[0].len() - 1;
            let cols: Vec<String> =
                (0..8).map(|f| fmt_mean_sd(&fig.iter().map(|s| s[m][f]).collect::<Vec<_>>())).collect();
            rows[v].push(format!("| {name} | {} |", cols.join(" | ")));
        }
    }
    for ((variant, fig), rows) in variants.iter().zip(&figures).zip(&rows) {
        println!(
            "\n### Bormann et al. maps over chain seeds 1..={} ({} iterations, {mode}{variant}): mean ± standard deviation\n",
            o.seeds, o.iterations
        );
        println!("| map | precision | recall | link precision | link recall | precision (furnished) | recall (furnished) | link precision (furnished) | link recall (furnished) |");
        println!("|---|---|---|---|---|---|---|---|---|");
        for row in rows {
            println!("{row}");
        }
        let means: Vec<Vec<f64>> =
            (0..8).map(|f| fig.iter().map(|s| mean(&s.iter().map(|m| m[f]).collect::<Vec<_>>())).collect()).collect();
        let cols: Vec<String> = means.iter().map(|v| fmt_mean_sd(v)).collect();
        println!("| **mean** | {} |", cols.join(" | "));
        let sum = |idx: [usize; 4]| idx.iter().map(|&f| mean(&means[f])).sum::<f64>();
        println!(
            "\nsum of the four segmentation means {:.3}, of the four link means {:.3}",
            sum([0, 1, 4, 5]),
            sum([2, 3, 6, 7])
        );
    }
    Ok(())
}

/// The kinds of synthetic map every synthetic table covers.
fn kinds() -> Vec<(&'static str, SynthConfig)> {
    vec![
        ("office 400x300", SynthConfig::default()),
        ("rotated 20 deg", SynthConfig { rotation_deg: 20.0, ..SynthConfig::default() }),
        ("furnished", SynthConfig { clutter: 0.1, ..SynthConfig::default() }),
        ("partly unexplored", SynthConfig { unexplored: 0.4, ..SynthConfig::default() }),
        ("large 1237x672", SynthConfig { width: 1237, height: 672, halls: 1, ..SynthConfig::default() }),
        // Two buildings at an angle (issue 13): the world model's units follow one direction.
        ("two wings 30 deg", SynthConfig { wing_deg: 30.0, ..SynthConfig::default() }),
        ("two wings 45 deg", SynthConfig { wing_deg: 45.0, ..SynthConfig::default() }),
    ]
}

fn synthetic(o: &Opts) -> Result<(), CliError> {
    println!("\n### Synthetic maps ({} iterations, {} generator seeds per kind)\n", o.iterations, o.seeds);
    println!("| kind | K(W,M) mean | K(W,M) min | furniture share | precision | recall | units (truth) |");
    println!("|---|---|---|---|---|---|---|");
    for (name, config) in kinds() {
        let (mut ks, mut ps, mut rs, mut units, mut truth_units) = (vec![], vec![], vec![], 0, 0);
        // Furniture cells read occupied or unknown inside rooms, and every world predicts a
        // unit's inside free (eq. 3.8), so K(W,M) <= 1 - this share even for the truth.
        let mut furniture = vec![];
        for seed in 0..o.seeds {
            let s = generate(&config, 100 + seed).map_err(|e| args::failed(name, e))?;
            let mut chain = explain(&s.map, o, seed + 1)?;
            let world = chain.best_world();
            ks.push(prediction_rate(s.map.classified(), &world));
            furniture.push(s.truth.object_cells.len() as f64 / s.map.classified().cells().len() as f64);
            let (_, labels) = chain.best_world_with_rooms(&o.rooms).map_err(rooms_failed)?;
            let labels = labels.map(|&l| l as u32);
            let truth: Grid<u32> = s.labels.map(|&l| l as u32);
            let score = score_segmentation(&labels, &truth);
            ps.push(score.precision);
            rs.push(score.recall);
            units += world.units.len();
            truth_units += s.truth.units.len();
        }
        let min = ks.iter().cloned().fold(f64::INFINITY, f64::min);
        println!(
            "| {name} | {:.4} | {:.4} | {:.3} | {:.3} | {:.3} | {:.1} ({:.1}) |",
            mean(&ks),
            min,
            mean(&furniture),
            mean(&ps),
            mean(&rs),
            units as f64 / o.seeds as f64,
            truth_units as f64 / o.seeds as f64
        );
    }
    Ok(())
}

/// One chain against a chain per wing (`floorplan::wings`, issue 13): K(W,M) of the world, the
/// angles its units follow and the time, on the two-wing kinds and every Bormann map (plain
/// and furnished). The segmentation is the first chain's in both, so it is not repeated here.
fn wings(dir: &Path, o: &Opts) -> Result<(), CliError> {
    use ksmcmc::floorplan::wings::{WingConfig, Wings};
    println!("\n### One chain against a chain per wing ({} iterations per chain, seed 1)\n", o.iterations);
    println!("| map | wings | K(W,M) one chain | K(W,M) wings | units (angles) | seconds one / wings |");
    println!("|---|---|---|---|---|---|");
    let mut maps: Vec<(String, OccupancyMap)> = Vec::new();
    for (name, config) in kinds().into_iter().filter(|(_, c)| c.wing_deg != 0.0) {
        for seed in 0..o.seeds.min(3) {
            let s = generate(&config, 100 + seed).map_err(|e| args::failed(name, e))?;
            maps.push((format!("{name}, floor {}", 100 + seed), s.map));
        }
    }
    let bormann = dir.join("bormann2016");
    for name in bormann_names(&bormann)? {
        for suffix in ["", "_furnitures"] {
            let mut map = args::load_map(&bormann.join(format!("{name}{suffix}.png")))?;
            map.set_classifier(Classifier::auto()).map_err(|e| args::failed("classifier", e))?;
            maps.push((format!("{name}{suffix}"), map));
        }
    }
    for (name, map) in maps {
        let t0 = std::time::Instant::now();
        let mut one = explain(&map, o, 1)?;
        let k_one = prediction_rate(map.classified(), &one.best_world_with_rooms(&o.rooms).map_err(rooms_failed)?.0);
        let t_one = t0.elapsed().as_secs_f64();
        let t0 = std::time::Instant::now();
        let w = Wings::run(&map, &o.config, &WingConfig::default(), 1, o.iterations, &o.rooms)
            .map_err(|e| CliError::Failed(e.to_string()))?;
        let t_wings = t0.elapsed().as_secs_f64();
        // A set: each angle once, in order.
        let angles: Vec<String> = w
            .world
            .units
            .iter()
            .map(|u| format!("{:.0}", w.world.unit_frame(u).angle.to_degrees()))
            .collect::<std::collections::BTreeSet<_>>()
            .into_iter()
            .collect();
        println!(
            "| {name} | {} | {k_one:.4} | {:.4} | {} ({}) | {t_one:.1} / {t_wings:.1} |",
            w.chains.len().saturating_sub(1).max(1),
            prediction_rate(map.classified(), &w.world),
            w.world.units.len(),
            angles.join(", ")
        );
    }
    Ok(())
}

/// Weak prior versus knowledge supervision (the comparison of Fig. 3.34).
fn knowledge(dir: &Path, o: &Opts) -> Result<(), CliError> {
    use ksmcmc::floorplan::metrics::{defect_pairs, defects};
    println!("\n### Weak prior versus knowledge supervision ({} iterations)\n", o.iterations);
    println!("| maps | mode | K(W,M) | unit count error | defects | type accuracy |");
    println!("|---|---|---|---|---|---|");

    for enabled in [false, true] {
        let mode = if enabled { "knowledge" } else { "weak prior" };
        let o2 = o.with_knowledge(enabled);
        let (mut ks, mut errs, mut defs, mut typed, mut right) = (vec![], vec![], vec![], 0u32, 0u32);
        for seed in 0..o.seeds {
            let s = generate(&SynthConfig::default(), 200 + seed).map_err(|e| args::failed("synth", e))?;
            let w = explain(&s.map, &o2, seed + 1)?.best_world_typed();
            ks.push(prediction_rate(s.map.classified(), &w));
            errs.push((w.units.len() as f64 - s.truth.units.len() as f64).abs());
            if let Some(d) = defects(&w) {
                defs.push(d);
            }
            // Type accuracy: each unit against the truth unit it overlaps most (IoU > 0.5).
            for u in &w.units {
                let best = s
                    .truth
                    .units
                    .iter()
                    .map(|t| {
                        let inter = u.rect().intersection(&t.rect()).map_or(0, |i| i.area());
                        (inter as f64 / (u.rect().area() + t.rect().area() - inter) as f64, t.kind)
                    })
                    .max_by(|a, b| a.0.total_cmp(&b.0));
                if let Some((_, kind)) = best.filter(|b| b.0 > 0.5) {
                    typed += 1;
                    right += (kind == u.kind) as u32;
                }
            }
        }
        println!(
            "| synthetic office, {} seeds | {mode} | {:.4} | {:.1} | {:.3} | {:.3} ({typed} matched units) |",
            o.seeds,
            mean(&ks),
            mean(&errs),
            mean(&defs),
            right as f64 / typed.max(1) as f64
        );
        let path = dir.join("radish/ubremen-cartesium.png");
        if path.exists() {
            let mut map = args::load_map(&path)?;
            map.set_classifier(Classifier::default()).map_err(|e| args::failed("classifier", e))?;
            let (mut ks, mut defs, mut units, mut pairs) = (vec![], vec![], vec![], [0u32; 2]);
            for seed in 1..=o.seeds.min(3) {
                let w = explain(&map, &o2, seed)?.best_world_typed();
                ks.push(prediction_rate(map.classified(), &w));
                units.push(w.units.len() as f64);
                // The share of this world (`defects`) and the counts pooled over the seeds.
                let (bad, all) = defect_pairs(&w);
                if all > 0 {
                    defs.push(bad as f64 / all as f64);
                }
                pairs[0] += bad;
                pairs[1] += all;
            }
            // Cartesium has few adjacent room pairs per world: the pooled counts say how few.
            println!(
                "| ubremen-cartesium, {} seeds | {mode} | {:.4} | ({:.1} units) | {:.3} ({} of {} pairs) | no truth |",
                o.seeds.min(3),
                mean(&ks),
                mean(&units),
                mean(&defs),
                pairs[0],
                pairs[1]
            );
        }
    }
    Ok(())
}

/// Knowledge supervision against the weak prior on the same maps with the same chain seeds:
/// the paired difference of K(W,M) per kind, so that "knowledge must not lose K(W,M)" can be
/// told from seed-to-seed noise.
fn paired(o: &Opts) -> Result<(), CliError> {
    println!("\n### Knowledge minus weak prior, paired ({} iterations, {} seeds per kind)\n", o.iterations, o.seeds);
    println!("| kind | K(W,M) knowledge | K(W,M) weak | difference (standard error) | seeds better / worse | units knowledge / weak (truth) |");
    println!("|---|---|---|---|---|---|");
    for (name, synth) in kinds() {
        let (mut k, mut diffs, mut units, mut truth) = ([vec![], vec![]], vec![], [0usize; 2], 0usize);
        for seed in 0..o.seeds {
            let s = generate(&synth, 100 + seed).map_err(|e| args::failed(name, e))?;
            truth += s.truth.units.len();
            for (m, enabled) in [true, false].into_iter().enumerate() {
                let w = explain(&s.map, &o.with_knowledge(enabled), seed + 1)?.best_world();
                k[m].push(prediction_rate(s.map.classified(), &w));
                units[m] += w.units.len();
            }
            diffs.push(k[0][seed as usize] - k[1][seed as usize]);
        }
        let d = mean(&diffs);
        let n = diffs.len() as f64;
        let se = if diffs.len() > 1 {
            (diffs.iter().map(|x| (x - d) * (x - d)).sum::<f64>() / (n - 1.0)).sqrt() / n.sqrt()
        } else {
            f64::NAN
        };
        // Differences under 1e-5 (about one cell in 100,000) are ties.
        let better = diffs.iter().filter(|&&x| x > 1e-5).count();
        let worse = diffs.iter().filter(|&&x| x < -1e-5).count();
        println!(
            "| {name} | {:.4} | {:.4} | {:+.5} ({:.5}) | {better} / {worse} | {:.1} / {:.1} ({:.1}) |",
            mean(&k[0]),
            mean(&k[1]),
            d,
            se,
            units[0] as f64 / n,
            units[1] as f64 / n,
            truth as f64 / n
        );
    }
    Ok(())
}

/// The synthetic kinds of the room-layer table (seeds 300 onwards, not used elsewhere).
fn room_kinds() -> Vec<(&'static str, SynthConfig)> {
    let d = SynthConfig::default();
    vec![
        ("hall", SynthConfig { width: 600, halls: 1, ..d.clone() }),
        ("two corridors", SynthConfig { width: 500, height: 400, corridors: Some(2), ..d.clone() }),
        ("cluttered", SynthConfig { clutter: 0.1, ..d.clone() }),
        ("rotated 20 deg", SynthConfig { rotation_deg: 20.0, ..d.clone() }),
        ("many storage", SynthConfig { width: 500, others: 6, ..d }),
    ]
}

/// Room count and types of one explained synthetic floor against its truth: (rooms, truth
/// units, truth units matched, matched units whose room has their type).
fn room_truth(s: &ksmcmc::floorplan::synth::Synthetic, o: &Opts, seed: u64) -> Result<[usize; 4], CliError> {
    let mut chain = explain(&s.map, o, seed)?;
    let (world, labels) = chain.best_world_with_rooms(&o.rooms).map_err(rooms_failed)?;
    let (truth, labels) = (s.labels.map(|&l| l as u32), labels.map(|&l| l as u32));
    let (matched, right) = crate::realistic_eval::units_typed_right(&world, &labels, &truth, &s.truth.units);
    Ok([world.rooms.len(), s.truth.units.len(), matched, right])
}

/// The room layer against synthetic truth, knowledge against weak prior on the same floors
/// and chain seeds.
fn rooms(o: &Opts) -> Result<(), CliError> {
    println!(
        "\n### Rooms against synthetic truth ({} iterations, {} seeds per kind from {})\n",
        o.iterations,
        o.seeds,
        o.rooms_from()
    );
    println!("| kind | mode | rooms (truth units) | type accuracy (matched units) |");
    println!("|---|---|---|---|");
    // Per mode (knowledge, weak prior): matched units and those typed right, over all kinds.
    let mut pooled = [[0usize; 2]; 2];
    for (name, synth) in room_kinds() {
        for (m, enabled) in [true, false].into_iter().enumerate() {
            let mut sum = [0usize; 4];
            for seed in 0..o.seeds {
                let s = generate(&synth, o.rooms_from() + seed).map_err(|e| args::failed(name, e))?;
                let r = room_truth(&s, &o.with_knowledge(enabled), seed + 1)?;
                for (a, b) in sum.iter_mut().zip(r) {
                    *a += b;
                }
            }
            let n = o.seeds as f64;
            let mode = if enabled { "knowledge" } else { "weak prior" };
            println!(
                "| {name} | {mode} | {:.1} ({:.1}) | {:.3} ({}) |",
                sum[0] as f64 / n,
                sum[1] as f64 / n,
                sum[3] as f64 / sum[2].max(1) as f64,
                sum[2]
            );
            pooled[m] = [pooled[m][0] + sum[2], pooled[m][1] + sum[3]];
        }
    }
    for (mode, [units, right]) in ["knowledge", "weak prior"].iter().zip(pooled) {
        println!("| **all kinds** | {mode} | | {:.3} ({units}) |", right as f64 / units.max(1) as f64);
    }
    Ok(())
}

/// Route stretch on explained synthetic floors: per kind, the mean and largest ratio of route
/// length over shortest free path, with how many routes the room graph had none for.
fn routes(o: &Opts) -> Result<(), CliError> {
    use ksmcmc::floorplan::route::{study::stretch, RoutePlanner};
    const PAIRS: usize = 200;
    println!(
        "\n### Routes on explained synthetic floors ({} iterations, {} seeds per kind from 300, {PAIRS} pairs each)\n",
        o.iterations, o.seeds
    );
    println!("| kind | routes | mean ratio | max ratio | worst floor (seed) | planned on cells | unreachable pairs | ms per route |");
    println!("|---|---|---|---|---|---|---|---|");
    for (name, synth) in room_kinds() {
        let (mut pairs, mut sum, mut max, mut worst, mut on_cells, mut unreachable) = (0, 0.0, 0.0f64, 0, 0, 0);
        let mut seconds = 0.0;
        for seed in 0..o.seeds {
            let s = generate(&synth, 300 + seed).map_err(|e| args::failed(name, e))?;
            let mut chain = explain(&s.map, o, seed + 1)?;
            let (world, labels) = chain.best_world_with_rooms(&o.rooms).map_err(rooms_failed)?;
            let map = s.map.classified().clone();
            let mut planner =
                RoutePlanner::new(map, labels, &world, s.map.yaml().resolution).map_err(|e| args::failed(name, e))?;
            // The time includes a shortest free path per pair (the reference), as a route does.
            let t0 = std::time::Instant::now();
            let st = stretch(&mut planner, PAIRS, seed + 1);
            seconds += t0.elapsed().as_secs_f64();
            pairs += st.pairs;
            sum += st.mean * st.pairs as f64;
            if st.max > max {
                (max, worst) = (st.max, 300 + seed);
            }
            on_cells += st.on_cells;
            unreachable += st.unreachable;
        }
        println!(
            "| {name} | {pairs} | {:.4} | {max:.4} | {worst} | {on_cells} | {unreachable} | {:.1} |",
            sum / pairs.max(1) as f64,
            1000.0 * seconds / (pairs + unreachable).max(1) as f64
        );
    }
    Ok(())
}

fn cartesium(dir: &Path, o: &Opts) -> Result<(), CliError> {
    let path = dir.join("radish/ubremen-cartesium.png");
    let mut map = args::load_map(&path)?;
    map.set_classifier(Classifier::default()).map_err(|e| args::failed("classifier", e))?;
    // The rooms of the map as `ksmcmc floorplan` classifies it (background grays from the
    // histogram), where issue 10 measures them; K(W,M) above is on eq. 3.7's classes, as
    // Tab. 3.7 reports it.
    let auto = args::load_classified(&path, "auto")?;
    let ks: Vec<f64> = (1..=o.seeds)
        .map(|seed| explain(&map, o, seed).map(|c| prediction_rate(map.classified(), &c.best_world())))
        .collect::<Result<_, _>>()?;
    let mut rooms = Vec::new();
    for seed in 1..=o.seeds {
        let mut chain = explain(&auto, o, seed)?;
        let k = prediction_rate(auto.classified(), &chain.best_world());
        rooms.push((k, chain.best_world_with_rooms(&o.rooms).map_err(rooms_failed)?.0.rooms));
    }
    let min = ks.iter().cloned().fold(f64::INFINITY, f64::min);
    let max = ks.iter().cloned().fold(0.0, f64::max);
    println!("\n### Radish ubremen-cartesium ({} iterations, seeds 1..={})\n", o.iterations, o.seeds);
    println!("| K(W,M) mean | min | max | per seed |");
    println!("|---|---|---|---|");
    let per: Vec<String> = ks.iter().map(|k| format!("{k:.4}")).collect();
    println!("| {:.4} | {:.4} | {:.4} | {} |", mean(&ks), min, max, per.join(" "));
    println!(
        "\nRooms per seed, the map classified as `ksmcmc floorplan` does (issue 10's floors: K at \
         least 0.936, at most 35 rooms, at most 20 % of them other). The share of other among \
         the typed rooms leaves out the `unknown` ones, fans of rays nobody would type:\n"
    );
    println!("| seed | K(W,M) | rooms | room | corridor | hall | other | unknown | other share | among typed |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (seed, (k, rooms)) in rooms.iter().enumerate() {
        let count = |t: UnitType| rooms.iter().filter(|r| r.kind == t).count();
        let n = rooms.len();
        let other = count(UnitType::Other) as f64;
        println!(
            "| {} | {k:.4} | {n} | {} | {} | {} | {} | {} | {:.2} | {:.2} |",
            seed + 1,
            count(UnitType::Room),
            count(UnitType::Corridor),
            count(UnitType::Hall),
            count(UnitType::Other),
            count(UnitType::Unknown),
            other / n.max(1) as f64,
            other / (n - count(UnitType::Unknown)).max(1) as f64
        );
    }
    Ok(())
}

/// Room-layer settings from a JSON file (missing fields take their defaults).
fn room_config(path: &Path) -> Result<RoomConfig, CliError> {
    let text = std::fs::read_to_string(path).map_err(|e| args::failed(path.display(), e))?;
    RoomConfig::from_json(&text).map_err(|e| args::failed(format!("{} (room-layer settings)", path.display()), e))
}

pub fn run(argv: Vec<OsString>) -> Result<(), CliError> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_args(argv);
    let mut dir = PathBuf::from("../shared/datasets");
    let mut o = Opts {
        iterations: 20_000,
        seeds: 6,
        config: ChainConfig::default(),
        more_rules: Vec::new(),
        rooms: RoomConfig::default(),
        more_rooms: Vec::new(),
        learn: None,
        cases: None,
        synth_from: None,
    };
    let mut only: Option<String> = None;
    let mut rules: Option<String> = None;
    while let Some(arg) = parser.next()? {
        match arg {
            Long("datasets") => dir = args::path(parser.value()?),
            Long("iterations") => o.iterations = args::value("--iterations", parser.value()?)?,
            Long("seeds") => o.seeds = args::value("--seeds", parser.value()?)?,
            Long("only") => only = Some(args::value("--only", parser.value()?)?),
            Long("config") => {
                let p = args::path(parser.value()?);
                let text = std::fs::read_to_string(&p).map_err(|e| args::failed(p.display(), e))?;
                o.config = ChainConfig::from_json(&text).map_err(|e| args::failed(p.display(), e))?;
            }
            Long("room-rules") => rules = Some(crate::floorplan::room_rules(&args::path(parser.value()?))?),
            Long("also-room-rules") => {
                let p = args::path(parser.value()?);
                o.more_rules.push((p.display().to_string(), crate::floorplan::room_rules(&p)?));
            }
            Long("room-config") => o.rooms = room_config(&args::path(parser.value()?))?,
            Long("also-room-config") => {
                let p = args::path(parser.value()?);
                o.more_rooms.push((p.display().to_string(), room_config(&p)?));
            }
            Long("learn") => o.learn = Some(args::path(parser.value()?)),
            Long("cases") => o.cases = Some(args::path(parser.value()?)),
            Long("synth-from") => o.synth_from = Some(args::value("--synth-from", parser.value()?)?),
            Long("help") | Short('h') => {
                print!("{HELP}");
                return Ok(());
            }
            _ => return Err(arg.unexpected().into()),
        }
    }
    // After --config, whichever came first.
    if rules.is_some() {
        o.config.knowledge.room_kb = rules;
    }
    if o.seeds == 0 {
        return Err(CliError::Usage("--seeds must be at least 1".into()));
    }
    if let Some(set) = only.as_deref().filter(|s| !SETS.contains(s)) {
        return Err(CliError::Usage(format!("--only {set}: no such set (one of {})", SETS.join(", "))));
    }
    run_sets(&dir, &o, only.as_deref())
}

/// Runs the evaluation of each set, in the order of the report, or only of set `only`.
fn run_sets(dir: &Path, o: &Opts, only: Option<&str>) -> Result<(), CliError> {
    let want = |s: &str| only.is_none_or(|set| set == s);
    if want("cartesium") {
        cartesium(dir, o)?;
    }
    if want("synthetic") {
        synthetic(o)?;
    }
    if want("bormann") {
        bormann(dir, o)?;
    }
    if want("knowledge") {
        knowledge(dir, o)?;
    }
    if want("paired") {
        paired(o)?;
    }
    if want("paired-bormann") {
        paired_bormann(dir, o)?;
    }
    if want("bormann-seeds") {
        bormann_seeds(dir, o)?;
    }
    if want("rooms") {
        rooms(o)?;
    }
    if want("routes") {
        routes(o)?;
    }
    if want("wings") {
        wings(dir, o)?;
    }
    if want("scale") {
        scale(dir, o)?;
    }
    if want("doors") {
        doors(dir, o)?;
    }
    if want("format") {
        format(dir, o)?;
    }
    if want("loo") {
        loo(dir, o)?;
    }
    if want("frontier") {
        let config = o.config.clone();
        crate::frontier_eval::frontier(&crate::frontier_eval::Options {
            iterations: o.iterations,
            config,
            learn: o.learn.as_deref(),
            cases: o.cases.as_deref(),
        })?;
    }
    if want("goals") {
        crate::goals_eval::goals(o.iterations)?;
    }
    if want("settle") {
        crate::settle_eval::settle(dir, &o.config, &o.rooms, o.seeds)?;
    }
    if want("realistic") {
        crate::realistic_eval::realistic(&o.config, &o.rooms, o.iterations, o.seeds, o.synth_from)?;
    }

    Ok(())
}
