use ksmcmc::floorplan::{Chain, ChainConfig};
use ksmcmc::grid::{Cell, Grid, OccupancyMap};
fn rooms_map() -> Grid<Cell> {
    let (w, h) = (64, 40);
    let mut g = Grid::new(w, h, Cell::Unknown);
    let mut room = |x0: usize, y0: usize, x1: usize, y1: usize| {
        for y in y0..=y1 {
            for x in x0..=x1 {
                let edge = x <= x0 + 1 || x >= x1 - 1 || y <= y0 + 1 || y >= y1 - 1;
                *g.at_mut(x, y) = if edge { Cell::Occupied } else { Cell::Free };
            }
        }
    };
    room(0, 0, 21, 25);
    room(20, 0, 41, 25);
    room(40, 0, 63, 25);
    room(0, 24, 63, 39);
    for y in 10..16 {
        for x in 20..22 {
            *g.at_mut(x, y) = Cell::Free;
            *g.at_mut(x + 20, y) = Cell::Free;
        }
    }
    for x in [8usize, 28, 50] {
        for dx in 0..6 {
            for y in 24..26 {
                *g.at_mut(x + dx, y) = Cell::Free;
            }
        }
    }
    *g.at_mut(10, 10) = Cell::Unknown;
    *g.at_mut(30, 30) = Cell::Occupied;
    g
}
fn main() {
    let map = OccupancyMap::from_classified(rooms_map());
    let oc = ksmcmc::floorplan::knowledge::ObjectCells::new(map.classified(), map.yaml().resolution, 2.0);
    println!(
        "res {} occ objects {} unk objects {}",
        map.yaml().resolution,
        oc.occupied_in(ksmcmc::floorplan::Rect::new(2, 2, 60, 36)),
        oc.unknown_in(ksmcmc::floorplan::Rect::new(2, 2, 60, 36))
    );
    for on in [false, true] {
        for seed in 0..6 {
            let mut c = ChainConfig::default();
            c.knowledge.enabled = on;
            let mut chain = Chain::new(&map, c, seed).unwrap();
            chain.step(8000);
            let w = chain.best_world_typed();
            let units: Vec<String> =
                w.units.iter().map(|u| format!("{}:{},{} {}x{}", u.kind.name(), u.x, u.y, u.w, u.h)).collect();
            println!(
                "on={on} seed={seed} K={:.4} lp={:.1} inf={} {:?}",
                chain.best_prediction_rate(),
                chain.best_log_posterior(),
                chain.inferences(),
                units
            );
        }
    }
}
