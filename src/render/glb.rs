//! A small glTF 2.0 binary (`.glb`) writer: triangle meshes with normals and plain
//! materials, one node per mesh, one scene. It is what the 3D world ([`super::model3d`]) needs
//! and no more, so no glTF crate is pulled in.
//!
//! The container (glTF 2.0, section "GLB File Format Specification") is a 12-byte header
//! (`glTF`, version 2, total length), a JSON chunk padded with spaces to a multiple of 4 bytes
//! and a binary chunk padded with zeros. All of a primitive's data sits in the one binary
//! buffer: positions and normals as `f32` triples (one buffer view each, target
//! `ARRAY_BUFFER`), indices as `u32` (target `ELEMENT_ARRAY_BUFFER`). Position accessors carry
//! their `min` and `max`, as the specification requires.
//!
//! ```
//! use ksmcmc::render::glb::{Glb, Primitive};
//! let mut glb = Glb::new();
//! let red = glb.material("red", [1.0, 0.0, 0.0, 1.0]);
//! let triangle = Primitive {
//!     positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
//!     normals: vec![[0.0, 0.0, 1.0]; 3],
//!     indices: vec![0, 1, 2],
//!     material: red,
//! };
//! glb.node("triangle", vec![triangle], None);
//! let bytes = glb.to_bytes();
//! assert_eq!(&bytes[0..4], b"glTF");
//! assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize, bytes.len());
//! assert_eq!(bytes.len() % 4, 0);
//! ```

use serde_json::{json, Value};

/// `ARRAY_BUFFER`: a buffer view of vertex attributes.
const ARRAY_BUFFER: u32 = 34962;
/// `ELEMENT_ARRAY_BUFFER`: a buffer view of indices.
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
/// Component types.
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
/// Primitive mode: triangles.
const TRIANGLES: u32 = 4;

/// One triangle list with one material.
#[derive(Debug, Clone, PartialEq)]
pub struct Primitive {
    /// Vertex positions, metres.
    pub positions: Vec<[f32; 3]>,
    /// Unit normals, one per vertex.
    pub normals: Vec<[f32; 3]>,
    /// Triangles, three vertex indices each, counter-clockwise seen from the front.
    pub indices: Vec<u32>,
    /// A material made by [`Glb::material`].
    pub material: usize,
}

/// A glTF document being built (see the module docs).
#[derive(Debug, Clone, Default)]
pub struct Glb {
    materials: Vec<Value>,
    meshes: Vec<Value>,
    nodes: Vec<Value>,
    accessors: Vec<Value>,
    views: Vec<Value>,
    bin: Vec<u8>,
}

impl Glb {
    /// An empty document.
    pub fn new() -> Glb {
        Glb::default()
    }

    /// A matte material of linear RGBA colour `rgba`; returns its index.
    pub fn material(&mut self, name: &str, rgba: [f32; 4]) -> usize {
        self.materials.push(json!({
            "name": name,
            "pbrMetallicRoughness": { "baseColorFactor": rgba, "metallicFactor": 0.0, "roughnessFactor": 0.9 },
        }));
        self.materials.len() - 1
    }

    /// The material named `name`, made with colour `rgba` if there is none yet.
    pub fn material_named(&mut self, name: &str, rgba: [f32; 4]) -> usize {
        match self.materials.iter().position(|m| m["name"] == name) {
            Some(i) => i,
            None => self.material(name, rgba),
        }
    }

    /// A node named `name` holding a mesh of `primitives` (primitives without triangles are
    /// left out, and a node with none is not added), with optional `extras` (any JSON kept with
    /// the node, for the application). Returns whether it was added.
    pub fn node(&mut self, name: &str, primitives: Vec<Primitive>, extras: Option<Value>) -> bool {
        let prims: Vec<Value> =
            primitives.iter().filter(|p| !p.indices.is_empty()).map(|p| self.primitive(p)).collect();
        if prims.is_empty() {
            return false;
        }
        self.meshes.push(json!({ "name": name, "primitives": prims }));
        let mut node = json!({ "name": name, "mesh": self.meshes.len() - 1 });
        if let Some(e) = extras {
            node["extras"] = e;
        }
        self.nodes.push(node);
        true
    }

    fn primitive(&mut self, p: &Primitive) -> Value {
        let mut min = [f32::INFINITY; 3];
        let mut max = [f32::NEG_INFINITY; 3];
        for v in &p.positions {
            for k in 0..3 {
                min[k] = min[k].min(v[k]);
                max[k] = max[k].max(v[k]);
            }
        }
        let n = p.positions.len();
        let pos = self.accessor(bytes_of(&p.positions), ARRAY_BUFFER, FLOAT, n, "VEC3", Some((min, max)));
        let nor = self.accessor(bytes_of(&p.normals), ARRAY_BUFFER, FLOAT, p.normals.len(), "VEC3", None);
        let idx: Vec<u8> = p.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let ind = self.accessor(idx, ELEMENT_ARRAY_BUFFER, UNSIGNED_INT, p.indices.len(), "SCALAR", None);
        json!({
            "attributes": { "POSITION": pos, "NORMAL": nor },
            "indices": ind,
            "material": p.material,
            "mode": TRIANGLES,
        })
    }

    /// Appends `data` as a buffer view (4-byte aligned) with one accessor over it.
    fn accessor(
        &mut self,
        data: Vec<u8>,
        target: u32,
        component: u32,
        count: usize,
        kind: &str,
        bounds: Option<([f32; 3], [f32; 3])>,
    ) -> usize {
        let offset = self.bin.len();
        self.bin.extend_from_slice(&data);
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        self.views.push(json!({ "buffer": 0, "byteOffset": offset, "byteLength": data.len(), "target": target }));
        let mut a =
            json!({ "bufferView": self.views.len() - 1, "componentType": component, "count": count, "type": kind });
        if let Some((min, max)) = bounds {
            a["min"] = json!(min);
            a["max"] = json!(max);
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    /// The `.glb` bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut doc = json!({
            "asset": { "version": "2.0", "generator": concat!("ksmcmc ", env!("CARGO_PKG_VERSION")) },
            "scene": 0,
            "scenes": [{ "nodes": (0..self.nodes.len()).collect::<Vec<_>>() }],
            "nodes": self.nodes,
        });
        // Empty arrays are not allowed in glTF: a document without meshes leaves them out.
        if !self.meshes.is_empty() {
            doc["meshes"] = json!(self.meshes);
            doc["materials"] = json!(self.materials);
            doc["accessors"] = json!(self.accessors);
            doc["bufferViews"] = json!(self.views);
            doc["buffers"] = json!([{ "byteLength": self.bin.len() }]);
        }
        if self.nodes.is_empty() {
            doc["scenes"] = json!([{}]);
            doc.as_object_mut().expect("an object").remove("nodes");
        }
        let mut text = serde_json::to_vec(&doc).expect("JSON serialises");
        text.resize(text.len().next_multiple_of(4), b' ');
        let bin_chunk = !self.bin.is_empty();
        let total = 12 + 8 + text.len() + if bin_chunk { 8 + self.bin.len() } else { 0 };
        let mut out = Vec::with_capacity(total);
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(total as u32).to_le_bytes());
        out.extend_from_slice(&(text.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&text);
        if bin_chunk {
            out.extend_from_slice(&(self.bin.len() as u32).to_le_bytes());
            out.extend_from_slice(b"BIN\0");
            out.extend_from_slice(&self.bin);
        }
        out
    }
}

fn bytes_of(v: &[[f32; 3]]) -> Vec<u8> {
    v.iter().flatten().flat_map(|f| f.to_le_bytes()).collect()
}

/// An sRGB colour byte as a linear glTF colour factor (glTF colour factors are linear; the
/// pictures' palettes are sRGB).
pub fn linear(c: u8) -> f32 {
    let s = c as f64 / 255.0;
    let l = if s <= 0.04045 { s / 12.92 } else { libm::pow((s + 0.055) / 1.055, 2.4) };
    l as f32
}
