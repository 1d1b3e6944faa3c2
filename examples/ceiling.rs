use ksmcmc::floorplan::metrics::prediction_rate;
use ksmcmc::floorplan::synth::{generate, SynthConfig};
use ksmcmc::grid::Cell;
fn main() {
    for (name, config) in
        [("office", SynthConfig::default()), ("furnished", SynthConfig { clutter: 0.1, ..SynthConfig::default() })]
    {
        for seed in 100..106 {
            let s = generate(&config, seed).unwrap();
            let m = s.map.classified();
            let k = prediction_rate(m, &s.truth);
            let mut obj_occ = 0;
            let mut obj_unk = 0;
            for c in &s.truth.object_cells {
                match m.at(c[0] as usize, c[1] as usize) {
                    Cell::Occupied => obj_occ += 1,
                    Cell::Unknown => obj_unk += 1,
                    _ => {}
                }
            }
            let n = m.cells().len() as f64;
            println!(
                "{name} {seed} truthK {k:.4} obj_occ {:.4} obj_unk {:.4} wall_t {}",
                obj_occ as f64 / n,
                obj_unk as f64 / n,
                config.wall_thickness
            );
        }
    }
}
