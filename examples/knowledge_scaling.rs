//! How the time of one knowledge inference grows with the world: the chain explains the large
//! synthetic map (seed 7) in the weak-prior mode, then the built-in indoor rules are inferred
//! on its first 10 to 47 units. BENCHMARKS.md ("Markov logic") quotes the output.
//!
//! `cargo run --release --example knowledge_scaling`

use ksmcmc::floorplan::knowledge::{Knowledge, KnowledgeConfig};
use ksmcmc::floorplan::synth::{generate, SynthConfig};
use ksmcmc::floorplan::{Chain, ChainConfig};
fn main() {
    let cfg = SynthConfig { width: 1237, height: 672, halls: 1, ..SynthConfig::default() };
    let s = generate(&cfg, 7).unwrap();
    let mut cc = ChainConfig::default();
    cc.knowledge.enabled = false;
    let mut chain = Chain::new(&s.map, cc, 1).unwrap();
    chain.step(20000);
    let w = chain.best_world();
    println!("units {}", w.units.len());
    let mut k = Knowledge::new(&KnowledgeConfig::default()).unwrap();
    let t = std::time::Instant::now();
    let inf = k.infer(&w, 0.05).unwrap();
    println!("infer {:.1} ms, same {}", t.elapsed().as_secs_f64() * 1e3, inf.same_length.len());
    for n in [10usize, 20, 30, 40, 47] {
        let mut w2 = w.clone();
        w2.units.truncate(n);
        let ids: Vec<u32> = w2.units.iter().map(|u| u.id).collect();
        w2.doors.retain(|d| ids.contains(&d.units[0]) && ids.contains(&d.units[1]));
        let mut k = Knowledge::new(&KnowledgeConfig::default()).unwrap();
        let t = std::time::Instant::now();
        let _ = k.infer(&w2, 0.05).unwrap();
        println!("{n} units: {:.2} ms work {}", t.elapsed().as_secs_f64() * 1e3, k.last_work);
    }
}
