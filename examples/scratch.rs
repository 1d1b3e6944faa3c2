use ksmcmc::floorplan::{Chain, ChainConfig};
use ksmcmc::grid::{Limits, OccupancyMap};
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let iters: u64 = std::env::args().nth(2).map(|s| s.parse().unwrap()).unwrap_or(20000);
    let map = OccupancyMap::load(std::path::Path::new(&path), &Limits::default()).unwrap();
    let t0 = std::time::Instant::now();
    let mut cfg = ChainConfig::default();
    if let Ok(t) = std::env::var("WALL") {
        cfg.wall_thickness = Some(t.parse().unwrap());
    }
    if let Ok(j) = std::env::var("CFG") {
        cfg = serde_json::from_str(&j).unwrap();
    }
    let mut chain = Chain::new(&map, cfg, 1).unwrap();
    let setup = t0.elapsed().as_secs_f64();
    println!(
        "setup {:.3}s angle {:.2}deg world {:?} candidates {}",
        setup,
        chain.frame().angle.to_degrees(),
        chain.frame().world_size,
        chain.candidates().len()
    );
    let t1 = std::time::Instant::now();
    let mut done = 0;
    while done < iters {
        chain.step(2000);
        done += 2000;
        println!(
            "it {} lp {:.0} best {:.0} units {} K {:.4} acc {:.3} t {:.2}s",
            chain.iteration(),
            chain.log_posterior(),
            chain.best_log_posterior(),
            chain.units().len(),
            chain.prediction_rate(),
            chain.trace().acceptance(),
            t1.elapsed().as_secs_f64()
        );
    }
    let el = t1.elapsed().as_secs_f64();
    println!(
        "{} it in {:.2}s = {:.0} it/s; best K(map) {:.4}",
        iters,
        el,
        iters as f64 / el,
        chain.best_prediction_rate()
    );
    let t = chain.trace();
    for k in ksmcmc::floorplan::Kernel::ALL {
        println!("{:12} {:>7} {:>6}", k.name(), t.proposed[k.index()], t.accepted[k.index()]);
    }
    dump(&chain, "/tmp/w.ppm");
    println!(
        "confusion [cm][cw] (free,unk,occ): {:?} overlap {}",
        chain.explanation().confusion(),
        chain.explanation().overlap()
    );
    std::fs::write("/tmp/world.json", chain.best_world().to_json()).unwrap();
}
#[allow(dead_code)]
fn dump(chain: &Chain, path: &str) {
    let g = chain.world_map();
    let (units, _doors) = chain.current_rects();
    let mut img = vec![0u8; g.width() * g.height() * 3];
    for y in 0..g.height() {
        for x in 0..g.width() {
            let v = match g.at(x, y) {
                ksmcmc::grid::Cell::Free => 255,
                ksmcmc::grid::Cell::Unknown => 160,
                _ => 0,
            };
            let i = (y * g.width() + x) * 3;
            img[i] = v;
            img[i + 1] = v;
            img[i + 2] = v;
        }
    }
    for r in units {
        for y in r.y..r.bottom() {
            for x in r.x..r.right() {
                if r.on_border(x, y) {
                    let i = (y as usize * g.width() + x as usize) * 3;
                    img[i] = 0;
                    img[i + 1] = 0;
                    img[i + 2] = 255;
                }
            }
        }
    }
    let mut f = format!("P6 {} {} 255\n", g.width(), g.height()).into_bytes();
    f.extend(img);
    std::fs::write(path, f).unwrap();
}
