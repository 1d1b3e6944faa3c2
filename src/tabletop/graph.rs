//! The scene graph (Fig. 4.1 d, Fig. 4.17 - 4.23): the table at the root, arrows for stable
//! support, undirected edges for other contact, flags for hidden objects and false estimates.
//!
//! Node 0 is the table, node `i + 1` object `i`. Two boxes in contact are joined by
//!
//! * a [`EdgeKind::Support`] edge from the supporting box to the supported one when the
//!   premise of rule r10 holds: both are stable, they touch, and the supported one is higher
//!   (so r10 makes the first `supportive` and the second `supported`);
//! * a [`EdgeKind::Contact`] edge otherwise (an unstable contact, such as a box leaning on
//!   another, or two boxes side by side). Contact is symmetric; the edge points from the
//!   earlier node to the later one.
//!
//! Intersections are not edges: they are what makes an object a false estimate, and show as
//! its flag.
//!
//! ```
//! use ksmcmc::tabletop::{synth, ChainConfig, TabletopChain};
//! use ksmcmc::tabletop::graph::to_json;
//!
//! let scene = synth::generate(&synth::SynthConfig::default(), 11).unwrap();
//! let chain = TabletopChain::new(scene, ChainConfig::default(), 1).unwrap();
//! let json = to_json(&chain.best_analysis().unwrap().graph);
//! assert_eq!(json["nodes"][0]["id"], "table");
//! assert_eq!(json["nodes"].as_array().unwrap().len(), chain.scene().objects.len() + 1);
//! ```

use super::decision::{Decision, DecisionRule};
use super::evidence::Evidence;
use super::geometry::{contact_kind, ContactKind, Obb, Tolerances};
use super::knowledge::QueryProbabilities;
use petgraph::graph::{DiGraph, NodeIndex};
use petgraph::visit::EdgeRef;
use serde::Serialize;

/// A node: the table or an object.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GraphNode {
    /// The object's id, or `"table"`.
    pub id: String,
    /// Whether this is the table.
    pub is_table: bool,
    /// `stable(o)`.
    pub stable: bool,
    /// `hover(o)`.
    pub hover: bool,
    /// Query probabilities (all zero for the table, which rules r7 and r8 exclude).
    pub probabilities: QueryProbabilities,
    /// `hidden(o)` under the decision rule.
    pub hidden: Decision,
    /// `false(o)` under the decision rule.
    pub false_estimate: Decision,
}

impl GraphNode {
    /// Flagged as implying a hidden object (probability above the rule's `true_above`).
    pub fn hidden_flag(&self) -> bool {
        self.hidden == Decision::True
    }

    /// Flagged as a false estimate.
    pub fn false_flag(&self) -> bool {
        self.false_estimate == Decision::True
    }
}

/// What an edge means.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum EdgeKind {
    /// Stable support, from the supporting box to the supported one.
    Support,
    /// Contact without stable support (undirected).
    Contact,
}

/// An edge: its kind and the shape of the touching points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct GraphEdge {
    /// Support or contact.
    pub kind: EdgeKind,
    /// Vertex, edge or facet contact (section 4.5.5).
    pub touch: Option<ContactKind>,
}

/// The scene graph.
pub type SceneGraph = DiGraph<GraphNode, GraphEdge>;

/// Builds the scene graph of a state: `ids` and `boxes` per object, the table box, the
/// evidence, the query probabilities of every box (objects, then the table) and the decision
/// rule.
pub fn build(
    ids: &[&str],
    boxes: &[Obb],
    table: &Obb,
    evidence: &Evidence,
    probabilities: &[QueryProbabilities],
    rule: &DecisionRule,
    tol: &Tolerances,
) -> SceneGraph {
    let n = ids.len();
    let mut g = SceneGraph::with_capacity(n + 1, 2 * n);
    g.add_node(GraphNode {
        id: "table".into(),
        is_table: true,
        stable: true,
        hover: false,
        probabilities: QueryProbabilities::default(),
        hidden: Decision::False,
        false_estimate: Decision::False,
    });
    for (i, id) in ids.iter().enumerate() {
        let p = probabilities.get(i).copied().unwrap_or_default();
        g.add_node(GraphNode {
            id: id.to_string(),
            is_table: false,
            stable: evidence.stable(i),
            hover: evidence.hover(i),
            probabilities: p,
            hidden: rule.decide(p.hidden),
            false_estimate: rule.decide(p.false_estimate),
        });
    }
    // Box index (objects 0..n, table n) to node index (table 0, objects 1..=n).
    let node = |b: usize| NodeIndex::new(if b == n { 0 } else { b + 1 });
    let obb = |b: usize| if b == n { table } else { &boxes[b] };
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for a in 0..=n {
        for b in a + 1..=n {
            if evidence.contact(a, b) {
                pairs.push(if node(a) < node(b) { (a, b) } else { (b, a) });
            }
        }
    }
    pairs.sort_by_key(|&(a, b)| (node(a), node(b)));
    for (a, b) in pairs {
        let touch = contact_kind(obb(a), obb(b), tol);
        let (from, to, kind) = if evidence.supports(a, b) {
            (a, b, EdgeKind::Support)
        } else if evidence.supports(b, a) {
            (b, a, EdgeKind::Support)
        } else {
            (a, b, EdgeKind::Contact)
        };
        g.add_edge(node(from), node(to), GraphEdge { kind, touch });
    }
    g
}

/// The row of every node when the graph is drawn as a hierarchy, as in the dissertation's
/// figures: 0 for the table; for a supported object one below its lowest supporter (support
/// follows `higher`, a strict order, so there are no cycles); for an object nothing supports
/// one below the lowest supported object (or the table) it touches, so a box leaning on two
/// others hangs under them; 1 for the rest.
pub fn levels(g: &SceneGraph) -> Vec<u32> {
    let n = g.node_count();
    let mut level = vec![1u32; n];
    if n == 0 {
        return level;
    }
    level[0] = 0;
    let mut supported = vec![false; n];
    supported[0] = true;
    for e in g.edge_references().filter(|e| e.weight().kind == EdgeKind::Support) {
        supported[e.target().index()] = true;
    }
    for _ in 0..n {
        let mut changed = false;
        for e in g.edge_references().filter(|e| e.weight().kind == EdgeKind::Support) {
            let want = level[e.source().index()] + 1;
            if e.target().index() != 0 && level[e.target().index()] < want {
                level[e.target().index()] = want;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let settled = level.clone();
    for e in g.edge_references().filter(|e| e.weight().kind == EdgeKind::Contact) {
        for (a, b) in [(e.source().index(), e.target().index()), (e.target().index(), e.source().index())] {
            if !supported[a] && supported[b] {
                level[a] = level[a].max(settled[b] + 1);
            }
        }
    }
    level
}

/// Rounds a probability to three decimals for output.
fn round3(p: f64) -> f64 {
    (p * 1000.0).round() / 1000.0
}

/// The scene graph as JSON:
///
/// ```text
/// { "nodes": [ { "id", "p_hidden", "p_false", "hidden", "false",
///                "p_supported", "p_supportive", "stable", "hover",
///                "hidden_decision", "false_decision" } ],      // the table first
///   "edges": [ { "from", "to", "kind": "support" | "contact",
///                "touch": "vertex" | "edge" | "facet" } ] }
/// ```
///
/// `hidden` and `false` are true only when the probability is above the decision rule's
/// threshold (0.6); `hidden_decision` and `false_decision` give the three-way answer of
/// section 4.10.1 (`"true"`, `"false"` or `"undecided"`). Probabilities are rounded to three
/// decimals.
pub fn to_json(g: &SceneGraph) -> serde_json::Value {
    let nodes: Vec<_> = g
        .node_weights()
        .map(|n| {
            serde_json::json!({
                "id": n.id,
                "p_hidden": round3(n.probabilities.hidden),
                "p_false": round3(n.probabilities.false_estimate),
                "hidden": n.hidden_flag(),
                "false": n.false_flag(),
                "p_supported": round3(n.probabilities.supported),
                "p_supportive": round3(n.probabilities.supportive),
                "stable": n.stable,
                "hover": n.hover,
                "hidden_decision": n.hidden,
                "false_decision": n.false_estimate,
            })
        })
        .collect();
    let edges: Vec<_> = g
        .edge_references()
        .map(|e| {
            serde_json::json!({
                "from": g[e.source()].id,
                "to": g[e.target()].id,
                "kind": e.weight().kind,
                "touch": e.weight().touch,
            })
        })
        .collect();
    serde_json::json!({ "nodes": nodes, "edges": edges })
}
