//! Evidence generation (section 4.5.5): the ground atoms of Tab. 4.1 read off the boxes.
//!
//! An [`Evidence`] holds, for the objects and the table, which boxes are stable, which pairs
//! touch or intersect, which box is higher than which, and hence which boxes hover. It is what
//! the knowledge base is grounded with ([`super::knowledge`]), so everything the chain needs
//! from the geometry passes through here.
//!
//! Boxes are numbered `0..n` for the objects, in scene order, and `n` for the table. The
//! relations are kept for all pairs, so that moving one object updates one row and column
//! ([`Evidence::update`]) instead of recomputing the scene.
//!
//! By construction the evidence satisfies the hard rules of Tab. 4.3 that concern evidence
//! alone: no box is higher than, touches or intersects itself (r1 - r3), contact and
//! intersection are symmetric (r4, r5) and exclusive, `higher` is antisymmetric (r6), and the
//! table is stable (r9).

use super::geometry::{higher, polygon_overlap, relation, Obb, Relation, Tolerances};
use nalgebra::Vector2;

/// The evidence predicates of Tab. 4.1 for one configuration of boxes.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Evidence {
    n: usize,
    stable: Vec<bool>,
    relation: Vec<Relation>,
    higher: Vec<bool>,
}

/// Per-box data the relations need: the box and its footprint.
#[derive(Debug, Clone)]
pub struct Placed {
    /// The box.
    pub obb: Obb,
    /// Its footprint seen from above.
    pub footprint: Vec<Vector2<f64>>,
}

impl Placed {
    /// A box with its footprint.
    pub fn new(obb: Obb) -> Placed {
        Placed { footprint: obb.footprint(), obb }
    }
}

impl Evidence {
    /// The evidence of `objects` (boxes `0..n`) on `table` (box `n`).
    pub fn compute(objects: &[Placed], table: &Placed, tol: &Tolerances) -> Evidence {
        let n = objects.len();
        let m = n + 1;
        let mut ev =
            Evidence { n, stable: vec![false; m], relation: vec![Relation::Apart; m * m], higher: vec![false; m * m] };
        ev.stable[n] = true;
        for i in 0..n {
            ev.stable[i] = objects[i].obb.is_stable(tol.stable_angle);
            let get = |j: usize| if j == n { table } else { &objects[j] };
            for j in i + 1..m {
                ev.set_pair(i, j, &objects[i], get(j), tol);
            }
        }
        ev
    }

    /// Recomputes everything that involves object `i` after it moved to `objects[i]`.
    pub fn update(&mut self, i: usize, objects: &[Placed], table: &Placed, tol: &Tolerances) {
        let n = self.n;
        self.stable[i] = objects[i].obb.is_stable(tol.stable_angle);
        for j in 0..=n {
            if j != i {
                self.set_pair(i, j, &objects[i], if j == n { table } else { &objects[j] }, tol);
            }
        }
    }

    fn set_pair(&mut self, i: usize, j: usize, a: &Placed, b: &Placed, tol: &Tolerances) {
        let m = self.n + 1;
        let r = relation(&a.obb, &b.obb, tol);
        self.relation[i * m + j] = r;
        self.relation[j * m + i] = r;
        let stacked = polygon_overlap(&a.footprint, &b.footprint) > tol.footprint;
        self.higher[i * m + j] = stacked && a.obb.center.z > b.obb.center.z;
        self.higher[j * m + i] = stacked && b.obb.center.z > a.obb.center.z;
        debug_assert_eq!(self.higher[i * m + j], higher(&a.obb, &b.obb, tol));
    }

    /// Number of objects (the table is box `objects()`).
    pub fn objects(&self) -> usize {
        self.n
    }

    /// The index of the table.
    pub fn table(&self) -> usize {
        self.n
    }

    /// `stable(i)`.
    pub fn stable(&self, i: usize) -> bool {
        self.stable[i]
    }

    /// How boxes `i` and `j` relate.
    pub fn relation(&self, i: usize, j: usize) -> Relation {
        self.relation[i * (self.n + 1) + j]
    }

    /// `contact(i, j)`.
    pub fn contact(&self, i: usize, j: usize) -> bool {
        self.relation(i, j) == Relation::Contact
    }

    /// `intersect(i, j)`.
    pub fn intersect(&self, i: usize, j: usize) -> bool {
        self.relation(i, j) == Relation::Intersect
    }

    /// `higher(i, j)`.
    pub fn higher(&self, i: usize, j: usize) -> bool {
        self.higher[i * (self.n + 1) + j]
    }

    /// `hover(i)`: box `i` touches and intersects nothing, the table included.
    pub fn hover(&self, i: usize) -> bool {
        (0..=self.n).all(|j| self.relation(i, j) == Relation::Apart)
    }

    /// Whether `j` stably supports `i`: the premise of rule r10 with `o1 = i`, `o2 = j`
    /// (both stable, in contact, `i` higher).
    pub fn supports(&self, j: usize, i: usize) -> bool {
        self.stable(i) && self.stable(j) && self.contact(i, j) && self.higher(i, j)
    }

    /// A compact key identifying the evidence, for caching what depends only on it.
    pub fn key(&self) -> Vec<u64> {
        let mut bits = Vec::with_capacity(self.stable.len() + 3 * self.relation.len());
        bits.extend(self.stable.iter().copied());
        for r in &self.relation {
            bits.push(*r == Relation::Contact);
            bits.push(*r == Relation::Intersect);
        }
        bits.extend(self.higher.iter().copied());
        let mut key = vec![self.n as u64];
        key.extend(bits.chunks(64).map(|c| c.iter().enumerate().fold(0u64, |k, (i, &b)| k | (b as u64) << i)));
        key
    }

    /// The evidence as text in the knowledge-base format, one true atom per line (all others
    /// are false), naming the table `T` and object `i` as `names[i]`.
    pub fn to_database_text(&self, names: &[String]) -> String {
        let mut out = String::new();
        for line in self.atoms(names) {
            out.push_str(line.0);
            out.push('(');
            out.push_str(&line.1.join(","));
            out.push_str(")\n");
        }
        out
    }

    /// The true evidence atoms: predicate and constants, naming box `i` as `names[i]` (the
    /// table is `names[n]`).
    pub fn atoms<'a>(&self, names: &'a [String]) -> Vec<(&'static str, Vec<&'a str>)> {
        let m = self.n + 1;
        let name = |i: usize| names[i].as_str();
        let mut atoms = vec![("table", vec![name(self.n)])];
        for i in 0..m {
            if self.stable(i) {
                atoms.push(("stable", vec![name(i)]));
            }
        }
        for i in 0..m {
            for j in 0..m {
                match self.relation(i, j) {
                    Relation::Contact => atoms.push(("contact", vec![name(i), name(j)])),
                    Relation::Intersect => atoms.push(("intersect", vec![name(i), name(j)])),
                    Relation::Apart => {}
                }
            }
        }
        for i in 0..self.n {
            if self.hover(i) {
                atoms.push(("hover", vec![name(i)]));
            }
        }
        for i in 0..m {
            for j in 0..m {
                if self.higher(i, j) {
                    atoms.push(("higher", vec![name(i), name(j)]));
                }
            }
        }
        atoms
    }
}
