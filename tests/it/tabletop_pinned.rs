//! Same seed, same result on every platform: fingerprints of generated scenes and of chain
//! results, pinned. The same file runs natively (`cargo test`) and as WebAssembly under node:
//!
//! ```sh
//! CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUNNER=wasm-bindgen-test-runner \
//!     cargo test --target wasm32-unknown-unknown --no-default-features --test tabletop_pinned
//! ```
//!
//! Both must give the pinned numbers; a change to the generator, the chain or the random
//! stream shows here first.

use ksmcmc::render::tabletop::{draw_graph, draw_view, marks, ViewOptions};
use ksmcmc::tabletop::synth::{generate, SynthConfig};
use ksmcmc::tabletop::{ChainConfig, TabletopChain};

/// FNV-1a, 64 bits.
fn fnv(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf29ce484222325u64, |h, &b| (h ^ b as u64).wrapping_mul(0x100000001b3))
}

/// Per seed: the scene's JSON, the best poses and graph after 20 iterations, and the pixels of
/// both drawings.
fn fingerprints() -> Vec<[u64; 3]> {
    [1u64, 2, 3]
        .iter()
        .map(|&seed| {
            let config = SynthConfig { max_objects: 6, ..Default::default() };
            let scene = generate(&config, seed).unwrap();
            let text = scene.to_json();
            let mut chain = TabletopChain::new(scene, ChainConfig::default(), seed).unwrap();
            chain.step(20);
            let analysis = chain.best_analysis().unwrap();
            let result = format!("{:?}{}", chain.best_poses(), analysis.graph_json());
            let poses: Vec<_> = analysis.objects.iter().map(|o| o.pose).collect();
            let view = draw_view(
                chain.scene(),
                &poses,
                &marks(&analysis),
                &ViewOptions { max_width: 320, ..Default::default() },
            );
            let mut pixels = draw_graph(&analysis.graph).data().to_vec();
            pixels.extend_from_slice(view.data());
            [fnv(text.as_bytes()), fnv(result.as_bytes()), fnv(&pixels)]
        })
        .collect()
}

const PINNED: [[u64; 3]; 3] = [
    [16331683661394385157, 9257291849805413616, 12007389758441075808],
    [4942098108145060336, 727902367376726980, 15717149910485975405],
    [17334853337090394318, 12171916246891976074, 10596981940298296722],
];

#[cfg(not(target_arch = "wasm32"))]
#[test]
fn pinned_natively() {
    assert_eq!(fingerprints(), PINNED);
}

#[cfg(target_arch = "wasm32")]
#[wasm_bindgen_test::wasm_bindgen_test]
fn pinned_in_webassembly() {
    assert_eq!(fingerprints(), PINNED);
}
