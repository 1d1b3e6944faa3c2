//! The scene graph of a world (Fig. 3.8 c/d): units as nodes, joined by doors and by walls.
//!
//! Two units are *adjacent* (the relation R of the dissertation, "connection by a wall") when
//! their facing walls are at most two wall depths apart and they overlap along them; a door
//! joins two units directly.

use crate::floorplan::world::{UnitType, World};
use crate::geometry::{facing, Axis};
use petgraph::graph::{NodeIndex, UnGraph};
use serde::Serialize;

/// A node: one unit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct UnitNode {
    /// The unit's id in the world.
    pub id: u32,
    /// Its type.
    #[serde(rename = "type")]
    pub kind: UnitType,
}

/// How two units are connected.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Link {
    /// Through a door (its id).
    Door(u32),
    /// Through a shared wall.
    Adjacent,
}

/// The scene graph as an undirected petgraph graph.
pub type SceneGraph = UnGraph<UnitNode, Link>;

/// Builds the scene graph of `world`: a node per unit, an edge per door, and an `Adjacent` edge
/// for every pair of units sharing a wall without a door.
///
/// ```
/// use ksmcmc::floorplan::{graph::scene_graph, Unit, UnitType, World};
/// let mut w = World::empty(40, 20);
/// w.units.push(Unit::new(1, 0, 0, 20, 20, UnitType::Room));
/// w.units.push(Unit::new(2, 20, 0, 20, 20, UnitType::Corridor));
/// let g = scene_graph(&w);
/// assert_eq!((g.node_count(), g.edge_count()), (2, 1));
/// ```
pub fn scene_graph(world: &World) -> SceneGraph {
    let mut g = SceneGraph::default();
    let nodes: Vec<NodeIndex> = world.units.iter().map(|u| g.add_node(UnitNode { id: u.id, kind: u.kind })).collect();
    let index = |id: u32| world.units.iter().position(|u| u.id == id);
    let mut linked = std::collections::BTreeSet::new();
    for d in &world.doors {
        if let (Some(a), Some(b)) = (index(d.units[0]), index(d.units[1])) {
            g.add_edge(nodes[a], nodes[b], Link::Door(d.id));
            linked.insert((a.min(b), a.max(b)));
        }
    }
    let t = world.wall_thickness;
    for (i, a) in world.units.iter().enumerate() {
        for (j, b) in world.units.iter().enumerate() {
            let key = (i.min(j), i.max(j));
            // Walls are shared by units of one frame only (units at their own angle, issue 13).
            if i == j || linked.contains(&key) || world.unit_frame(a) != world.unit_frame(b) {
                continue;
            }
            let touching = [Axis::Horizontal, Axis::Vertical]
                .iter()
                .any(|&axis| facing(a.rect(), b.rect(), axis, 2 * t, t).is_some());
            if touching {
                linked.insert(key);
                g.add_edge(nodes[i], nodes[j], Link::Adjacent);
            }
        }
    }
    g
}

/// The scene graph as JSON: `{"nodes": [{"id", "type"}], "edges": [{"from", "to", "kind", "door"?}]}`.
pub fn to_json(g: &SceneGraph) -> serde_json::Value {
    let nodes: Vec<_> = g.node_weights().map(|n| serde_json::json!({"id": n.id, "type": n.kind})).collect();
    let edges: Vec<_> = g
        .edge_indices()
        .map(|e| {
            let (a, b) = g.edge_endpoints(e).expect("edge exists");
            let (from, to) = (g[a].id, g[b].id);
            match g[e] {
                Link::Door(id) => serde_json::json!({"from": from, "to": to, "kind": "door", "door": id}),
                Link::Adjacent => serde_json::json!({"from": from, "to": to, "kind": "adjacent"}),
            }
        })
        .collect();
    serde_json::json!({"nodes": nodes, "edges": edges})
}

/// The scene graph of `world` ([`scene_graph`], [`to_json`]) with its room layer:
/// `{"nodes", "edges", "rooms": [{"id", "type", "units", "area_m2", "doors", "opens_to"}]}`,
/// and where the map has frontiers `"placeholders": [{"id", "room", "x", "y", "width_m",
/// "p_new_room", "types"}]`, each a node joined to the room it opens from (`room`, 0 for none)
/// as in `world.json` ([`crate::floorplan::frontier`]). `graph.json` holds this.
pub fn world_json(world: &World) -> serde_json::Value {
    let mut v = to_json(&scene_graph(world));
    v["rooms"] = serde_json::to_value(&world.rooms).expect("rooms serialise");
    if !world.placeholders.is_empty() {
        v["placeholders"] = serde_json::to_value(&world.placeholders).expect("placeholders serialise");
    }
    v
}
