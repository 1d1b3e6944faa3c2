//! `ksmcmc tabletop SCENE.json --out DIR` (a scene graph from estimated poses) and
//! `ksmcmc tabletop-eval` (accuracy and speed on generated scenes).

use crate::args::{self, CliError};
use ksmcmc::render::encode_png;
use ksmcmc::render::tabletop::{draw_graph, draw_view, marks, ViewOptions};
use ksmcmc::tabletop::eval::{
    analyse_scene, dissertation_scenes, graph_signature, score, DissertationResult, EvalReport, GeneratedResult, Score,
    SpeedResult,
};
use ksmcmc::tabletop::scene::Scene;
use ksmcmc::tabletop::summary::{RunReport, Timings};
use ksmcmc::tabletop::synth::{generate, SynthConfig};
use ksmcmc::tabletop::{Analysis, ChainConfig, Decision, TabletopChain};
use std::ffi::OsString;
use std::path::PathBuf;
use std::time::Instant;

const HELP: &str = "\
Usage: ksmcmc tabletop SCENE.json --out DIR [options]

Builds the scene graph of a table-top scene from estimated 6D object poses: refines the poses
by knowledge-supervised MCMC (Liu 2014, chapter 4) and infers which objects hide another one
under them and which are false estimates. Writes:
  DIR/graph.json    nodes {id, p_hidden, p_false, hidden, false, ...} (the table has id
                    \"table\") and edges {from, to, kind: support | contact}; hidden / false
                    are true only for probabilities above 0.6
  DIR/graph.png     the scene graph (false estimates red, objects hiding another cyan)
  DIR/view.png      the boxes at their refined poses as the camera sees them
  DIR/report.json   iterations, seconds, ms_per_iteration, refined poses, evidence, and the
                    score against the scene's truth when it has one

Options:
  --iterations N    sweeps over all objects (default 100)
  --seed S          random seed (default 1); same seed, same result
  --config FILE     chain configuration JSON (any subset of fields; see the library docs)
";

pub fn run(argv: Vec<OsString>) -> Result<(), CliError> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_args(argv);
    let (mut scene_path, mut out, mut config_path) = (None::<PathBuf>, None::<PathBuf>, None::<PathBuf>);
    let (mut iterations, mut seed) = (100u32, 1u64);
    while let Some(arg) = parser.next()? {
        match arg {
            Value(v) if scene_path.is_none() => scene_path = Some(args::path(v)),
            Long("out") => out = Some(args::path(parser.value()?)),
            Long("iterations") => iterations = args::value("--iterations", parser.value()?)?,
            Long("seed") => seed = args::value("--seed", parser.value()?)?,
            Long("config") => config_path = Some(args::path(parser.value()?)),
            Long("help") | Short('h') => {
                print!("{HELP}");
                return Ok(());
            }
            _ => return Err(arg.unexpected().into()),
        }
    }
    let scene_path = args::required(scene_path, "a SCENE.json", "tabletop")?;
    let out = args::required(out, "--out DIR", "tabletop")?;
    let config = read_config(config_path.as_ref())?;
    let text = std::fs::read_to_string(&scene_path).map_err(|e| args::failed(scene_path.display(), e))?;
    let scene = Scene::from_json(&text).map_err(|e| args::failed(scene_path.display(), e))?;

    let start = Instant::now();
    let mut chain = TabletopChain::new(scene, config, seed).map_err(|e| args::failed(scene_path.display(), e))?;
    let setup = start.elapsed().as_secs_f64();
    let t = Instant::now();
    chain.step(iterations);
    let sampling = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let analysis = chain.best_analysis().map_err(|e| args::failed("inference", e))?;
    let inference = t.elapsed().as_secs_f64();
    let seconds = start.elapsed().as_secs_f64();

    let graph_json = analysis.graph_json();
    let poses: Vec<_> = analysis.objects.iter().map(|o| o.pose).collect();
    let view = draw_view(chain.scene(), &poses, &marks(&analysis), &ViewOptions::default());
    let timings = Timings { setup, sampling, inference, total: seconds };
    let report = RunReport::new(&chain, &analysis, &scene_path.display().to_string(), seed, iterations, timings);
    let pretty = |v: &serde_json::Value| serde_json::to_string_pretty(v).unwrap_or_default() + "\n";
    args::write(&out.join("graph.json"), pretty(&graph_json).as_bytes())?;
    args::write(&out.join("graph.png"), &encode_png(&draw_graph(&analysis.graph)))?;
    args::write(&out.join("view.png"), &encode_png(&view))?;
    args::write(&out.join("report.json"), report.to_json().as_bytes())?;
    print_objects(&analysis);
    println!(
        "{iterations} iterations in {:.1} ms ({:.3} ms per iteration); wrote {}",
        1000.0 * seconds,
        if iterations > 0 { 1000.0 * sampling / iterations as f64 } else { 0.0 },
        out.display()
    );
    Ok(())
}

/// One line per object: its probabilities and the flags decided true.
fn print_objects(analysis: &Analysis) {
    for o in &analysis.objects {
        let flag = |d: Decision, name: &str| if d == Decision::True { format!(" {name}") } else { String::new() };
        println!(
            "{:<12} false={:.3} hidden={:.3}{}{}",
            o.id,
            o.probabilities.false_estimate,
            o.probabilities.hidden,
            flag(o.false_estimate, "FALSE-ESTIMATE"),
            flag(o.hidden, "HIDES-AN-OBJECT"),
        );
    }
}

fn read_config(path: Option<&PathBuf>) -> Result<ChainConfig, CliError> {
    let config = match path {
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|e| args::failed(p.display(), e))?;
            ChainConfig::parse_json(&text).map_err(|e| args::failed(p.display(), e))?
        }
        None => ChainConfig::default(),
    };
    config.validate().map_err(|e| CliError::Usage(e.to_string()))?;
    Ok(config)
}

const EVAL_HELP: &str = "\
Usage: ksmcmc tabletop-eval [options]

Measures the table-top analysis on generated scenes (for BENCHMARKS.md):
  1. accuracy: N generated scenes (up to 10 objects each); the share of hidden / false flags
     (probability above 0.6) that agree with the truth, and of decided answers (above 0.6 or
     below 0.4) that do;
  2. the dissertation's test (section 4.10.1): 25 labelled scenes holding 10 objects with a
     hidden object under them and 5 false estimates, each analysed 20 times with different
     seeds: are all of them found every time, and is the scene graph the same every time?
  3. speed on scenes of exactly 8 objects: ms per iteration and for the whole analysis.

Options:
  --scenes N        generated scenes for part 1 (default 200)
  --iterations N    sweeps per analysis (default 100)
  --seed S          first scene seed (default 1)
  --repeats R       runs per scene in part 2 (default 20)
  --speed N         scenes for part 3 (default 20)
  --config FILE     chain configuration JSON
  --synth FILE      generator configuration JSON for all parts (any subset of the fields of
                    the library's SynthConfig; part 2 keeps its own object counts)
  --json FILE       also write the results as JSON
  --quick           parts 1 and 3 only
";

/// `tabletop-eval`'s options.
struct EvalOpts {
    scenes: u32,
    iterations: u32,
    seed: u64,
    repeats: u32,
    speed: u32,
    config: ChainConfig,
    synth: SynthConfig,
    json: Option<PathBuf>,
    quick: bool,
}

pub fn eval(argv: Vec<OsString>) -> Result<(), CliError> {
    let Some(o) = parse_eval(argv)? else { return Ok(()) };
    let (total, objects, accuracy_seconds) = eval_generated(&o)?;
    let dissertation = if o.quick { None } else { Some(eval_dissertation(&o)?) };
    let (per_iteration, whole, worst) = eval_speed(&o)?;
    let EvalOpts { scenes, iterations, speed, .. } = o;
    if let Some(p) = o.json {
        let generated = GeneratedResult {
            scenes,
            objects,
            iterations,
            score: total,
            flag_accuracy: total.flag_accuracy(),
            decision_accuracy: total.decision_accuracy(),
            ms_per_scene: 1000.0 * accuracy_seconds / scenes.max(1) as f64,
        };
        let speed = SpeedResult {
            objects: 8,
            scenes: speed,
            iterations,
            ms_per_iteration: per_iteration,
            analysis_ms: whole,
            analysis_ms_worst: worst,
        };
        args::write(&p, EvalReport { generated, dissertation, speed }.to_json().as_bytes())?;
    }
    Ok(())
}

fn fail(e: &dyn std::fmt::Display) -> CliError {
    CliError::Failed(e.to_string())
}

/// Parses `tabletop-eval`'s arguments and reads its configurations; `None` after `--help`.
fn parse_eval(argv: Vec<OsString>) -> Result<Option<EvalOpts>, CliError> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_args(argv);
    let (mut scenes, mut iterations, mut seed, mut repeats, mut speed) = (200u32, 100u32, 1u64, 20u32, 20u32);
    let (mut config_path, mut json_path, mut quick) = (None::<PathBuf>, None::<PathBuf>, false);
    let mut synth_path = None::<PathBuf>;
    while let Some(arg) = parser.next()? {
        match arg {
            Long("scenes") => scenes = args::value("--scenes", parser.value()?)?,
            Long("iterations") => iterations = args::value("--iterations", parser.value()?)?,
            Long("seed") => seed = args::value("--seed", parser.value()?)?,
            Long("repeats") => repeats = args::value("--repeats", parser.value()?)?,
            Long("speed") => speed = args::value("--speed", parser.value()?)?,
            Long("config") => config_path = Some(args::path(parser.value()?)),
            Long("json") => json_path = Some(args::path(parser.value()?)),
            Long("synth") => synth_path = Some(args::path(parser.value()?)),
            Long("quick") => quick = true,
            Long("help") | Short('h') => {
                print!("{EVAL_HELP}");
                return Ok(None);
            }
            _ => return Err(arg.unexpected().into()),
        }
    }
    let config = read_config(config_path.as_ref())?;
    let synth = match &synth_path {
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|e| args::failed(p.display(), e))?;
            SynthConfig::parse_json(&text).map_err(|e| args::failed(p.display(), e))?
        }
        None => SynthConfig::default(),
    };
    synth.validate().map_err(|m| CliError::Usage(format!("invalid generator configuration: {m}")))?;
    Ok(Some(EvalOpts { scenes, iterations, seed, repeats, speed, config, synth, json: json_path, quick }))
}

/// 1. Accuracy on generated scenes: the pooled score, the number of objects, the seconds taken.
fn eval_generated(o: &EvalOpts) -> Result<(Score, usize, f64), CliError> {
    let EvalOpts { scenes, iterations, seed, config, ref synth, .. } = *o;
    let mut total = Score::default();
    let mut objects = 0usize;
    let mut by_kind: std::collections::BTreeMap<String, [u32; 3]> = Default::default();
    let t = Instant::now();
    for k in 0..scenes {
        let scene = generate(synth, seed + k as u64).map_err(|e| fail(&e))?;
        let analysis = analyse_scene(&scene, &config, 1, iterations).map_err(|e| fail(&e))?;
        objects += scene.objects.len();
        total.merge(&score(&scene, &analysis));
        for (o, a) in scene.objects.iter().zip(&analysis.objects) {
            let kind = o.truth.as_ref().and_then(|t| t.kind.clone()).unwrap_or_default();
            let e = by_kind.entry(kind).or_default();
            e[0] += 1;
            e[1] += (a.hidden == Decision::Undecided) as u32;
            e[2] += (a.false_estimate == Decision::Undecided) as u32;
        }
    }
    let accuracy_seconds = t.elapsed().as_secs_f64();
    println!("1. Generated scenes: {scenes} scenes, {objects} objects, {iterations} iterations each");
    println!("   flags correct: {}/{} = {:.2} %", total.flags_correct, total.total, 100.0 * total.flag_accuracy());
    println!(
        "   decided and correct: {}/{} = {:.2} % (undecided answers count as wrong)",
        total.decided_correct,
        total.total,
        100.0 * total.decision_accuracy()
    );
    for (name, c) in [("hidden", total.hidden), ("false", total.false_estimate)] {
        println!(
            "   {name:<6}: {} positives; found {}, missed {} (undecided {}); {} false alarms; {} undecided of {} negatives",
            c.positives(),
            c.true_positive,
            c.false_negative,
            c.undecided_true,
            c.false_positive,
            c.undecided_false,
            c.total() - c.positives()
        );
    }
    for (kind, [n, uh, uf]) in &by_kind {
        println!("   {kind:<9} {n:>5} objects: undecided hidden {uh}, undecided false {uf}");
    }
    println!("   {:.1} ms per scene", 1000.0 * accuracy_seconds / scenes.max(1) as f64);
    Ok((total, objects, accuracy_seconds))
}

/// 2. The dissertation's test: each scene of its set analysed `repeats` times.
fn eval_dissertation(o: &EvalOpts) -> Result<DissertationResult, CliError> {
    let EvalOpts { iterations, seed, repeats, config, ref synth, .. } = *o;
    let set = dissertation_scenes(seed, synth).map_err(|e| fail(&e))?;
    let (mut hidden, mut falses) = (0, 0);
    for s in &set {
        for o in &s.objects {
            let t = o.truth.as_ref().expect("generated scenes carry truth");
            hidden += t.hidden as u32;
            falses += t.false_estimate as u32;
        }
    }
    let (mut all_found, mut stable_graphs, mut runs) = (0u32, 0u32, 0u32);
    let mut positives_found = 0u32;
    let mut false_alarms = 0u32;
    for s in &set {
        let mut signatures = std::collections::BTreeSet::new();
        let mut ok_every_run = true;
        for r in 0..repeats {
            let a = analyse_scene(s, &config, 1 + r as u64, iterations).map_err(|e| fail(&e))?;
            let sc = score(s, &a);
            runs += 1;
            positives_found += sc.hidden.true_positive + sc.false_estimate.true_positive;
            false_alarms += sc.hidden.false_positive + sc.false_estimate.false_positive;
            ok_every_run &= sc.flags_correct == sc.total;
            signatures.insert(graph_signature(&a));
        }
        all_found += ok_every_run as u32;
        stable_graphs += (signatures.len() == 1) as u32;
    }
    println!(
        "2. Dissertation test: {} scenes with {hidden} hidden objects and {falses} false estimates, {repeats} runs each",
        set.len()
    );
    println!(
        "   scenes inferred correctly in every run: {all_found}/{}; found {positives_found} of {} positives over all runs, {false_alarms} false alarms",
        set.len(),
        (hidden + falses) * repeats
    );
    println!("   scenes whose scene graph was the same in all {repeats} runs: {stable_graphs}/{}", set.len());
    Ok(DissertationResult {
        scenes: set.len(),
        hidden,
        false_estimates: falses,
        repeats,
        runs,
        scenes_correct_every_run: all_found,
        positives_found,
        positives_expected: (hidden + falses) * repeats,
        false_alarms,
        scenes_same_graph: stable_graphs,
    })
}

/// 3. Speed with 8 objects: mean ms per iteration, mean and worst ms per whole analysis.
fn eval_speed(o: &EvalOpts) -> Result<(f64, f64, f64), CliError> {
    let EvalOpts { iterations, seed, speed, config, ref synth, .. } = *o;
    let eight = SynthConfig { min_objects: 8, max_objects: 8, ..synth.clone() };
    let (mut per_iteration, mut whole, mut worst) = (Vec::new(), Vec::new(), 0f64);
    for k in 0..speed {
        let scene = generate(&eight, 10_000 + seed + k as u64).map_err(|e| fail(&e))?;
        let t = Instant::now();
        let mut chain = TabletopChain::new(scene, config, 1).map_err(|e| fail(&e))?;
        let t_steps = Instant::now();
        chain.step(iterations);
        let steps = t_steps.elapsed().as_secs_f64();
        chain.best_analysis().map_err(|e| fail(&e))?;
        let all = t.elapsed().as_secs_f64();
        per_iteration.push(1000.0 * steps / iterations.max(1) as f64);
        whole.push(1000.0 * all);
        worst = worst.max(1000.0 * all);
    }
    let mean = |v: &[f64]| if v.is_empty() { 0.0 } else { v.iter().sum::<f64>() / v.len() as f64 };
    println!(
        "3. Speed, 8 objects, {iterations} iterations: {:.3} ms per iteration, whole analysis {:.1} ms (worst {:.1} ms) over {speed} scenes",
        mean(&per_iteration),
        mean(&whole),
        worst
    );
    Ok((mean(&per_iteration), mean(&whole), worst))
}
