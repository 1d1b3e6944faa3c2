//! Knowledge bases (predicates, types, weighted formulas) and evidence databases.

use super::error::{ErrorKind, MlnError, Position, Source};
use super::logic::{cnf, fo_nnf, Cnf, Expr, FoLit, Term};
use super::syntax::{self, Name, Raw, Statement};
use std::collections::HashMap;
use std::fmt;

/// First-order clauses past this many are not precomputed; such formulas are converted one
/// grounding at a time, after the evidence has simplified them.
const FO_CNF_LIMIT: usize = 256;

/// A formula's weight: a real number, or hard (infinite).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Weight {
    /// A soft formula: worlds violating a grounding are `exp(w)` times less probable.
    Soft(f64),
    /// A hard formula: worlds violating a grounding have probability zero.
    Hard,
}

/// A declared predicate.
#[derive(Debug, Clone)]
pub struct Predicate {
    pub(crate) name: String,
    pub(crate) arg_types: Vec<u32>,
    pub(crate) at: Position,
}

impl Predicate {
    /// Its name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Its number of arguments.
    pub fn arity(&self) -> usize {
        self.arg_types.len()
    }
}

/// A variable of a formula, with its inferred type.
#[derive(Debug, Clone)]
pub(crate) struct Variable {
    pub name: String,
    pub ty: Option<u32>,
    pub at: Position,
}

/// A weighted (or hard) first-order formula.
#[derive(Debug, Clone)]
pub struct Formula {
    pub(crate) expr: Expr,
    pub(crate) vars: Vec<Variable>,
    /// Slots of the free (implicitly universally quantified) variables.
    pub(crate) free: Vec<u32>,
    pub(crate) weight: Weight,
    pub(crate) at: Position,
    pub(crate) text: String,
    /// Clausal forms of the formula and of its negation, when quantifier-free and small.
    pub(crate) cnf: Option<Cnf<FoLit>>,
    pub(crate) cnf_negated: Option<Cnf<FoLit>>,
}

impl Formula {
    /// Its weight.
    pub fn weight(&self) -> Weight {
        self.weight
    }

    /// Its text as written (without weight or final period).
    pub fn text(&self) -> &str {
        &self.text
    }

    /// Where it starts in the knowledge base.
    pub fn position(&self) -> Position {
        self.at
    }
}

/// A type (sort) of constants.
#[derive(Debug, Clone)]
pub(crate) struct TypeInfo {
    pub name: String,
    /// `type = {...}` in the knowledge base: the domain is closed.
    pub declared: Option<(Vec<u32>, Position)>,
    /// Constants the formulas mention at arguments of this type.
    pub mentioned: Vec<u32>,
}

/// A Markov logic network: declarations and weighted first-order formulas (the `L` of
/// Richardson and Domingos' `M_{L,C}`; the constants `C` come with the evidence).
#[derive(Debug, Clone, Default)]
pub struct Mln {
    pub(crate) types: Vec<TypeInfo>,
    pub(crate) predicates: Vec<Predicate>,
    pub(crate) formulas: Vec<Formula>,
    pub(crate) constants: Vec<String>,
    pub(crate) constant_index: HashMap<String, u32>,
    pub(crate) predicate_index: HashMap<String, u32>,
    pub(crate) type_index: HashMap<String, u32>,
}

impl Mln {
    /// Parses a knowledge base in the Alchemy / ProbCog text format (see the [module
    /// docs](super) for the grammar).
    pub fn parse(text: &str) -> Result<Mln, MlnError> {
        if text.len() > super::MAX_KB_BYTES {
            return Err(super::text_too_long("knowledge base", text.len(), super::MAX_KB_BYTES, "MAX_KB_BYTES"));
        }
        Self::parse_text(text).map_err(|e| e.in_text(Source::KnowledgeBase))
    }

    fn parse_text(text: &str) -> Result<Mln, MlnError> {
        let mut mln = Mln::default();
        let mut pending_checks: Vec<(u32, u32, Position)> = Vec::new(); // (type, constant, at)
        for st in syntax::parse_kb(text)? {
            match st {
                Statement::Domain { name, constants } => {
                    let t = mln.intern_type(&name.text);
                    if let Some((_, first)) = &mln.types[t as usize].declared {
                        let what = format!("the domain of type {}", name.text);
                        return Err(MlnError::at(ErrorKind::Redeclared { what, first: *first }, name.at));
                    }
                    let mut ids = Vec::new();
                    for c in &constants {
                        let id = mln.intern_constant(&c.text);
                        if !ids.contains(&id) {
                            ids.push(id);
                        }
                    }
                    mln.types[t as usize].declared = Some((ids, name.at));
                }
                Statement::Formula { weight, hard, formula, at, text } => {
                    if weight.is_none() && !hard {
                        mln.declare(formula, at)?;
                        continue;
                    }
                    let weight = if hard { Weight::Hard } else { Weight::Soft(weight.unwrap()) };
                    let f = mln.resolve(&formula, weight, at, text, &mut pending_checks)?;
                    mln.formulas.push(f);
                }
            }
        }
        for (t, c, at) in pending_checks {
            let ty = &mln.types[t as usize];
            if let Some((ids, _)) = &ty.declared {
                if !ids.contains(&c) {
                    let constant = mln.constants[c as usize].clone();
                    return Err(MlnError::at(ErrorKind::UnknownConstant { constant, type_name: ty.name.clone() }, at));
                }
            }
        }
        Ok(mln)
    }

    /// The declared predicates, in declaration order.
    pub fn predicates(&self) -> &[Predicate] {
        &self.predicates
    }

    /// The formulas, in file order.
    pub fn formulas(&self) -> &[Formula] {
        &self.formulas
    }

    /// The predicate called `name`.
    pub fn predicate(&self, name: &str) -> Option<&Predicate> {
        self.predicate_index.get(name).map(|&i| &self.predicates[i as usize])
    }

    /// The names of a predicate's argument types.
    pub fn argument_types(&self, predicate: &Predicate) -> Vec<&str> {
        predicate.arg_types.iter().map(|&t| self.types[t as usize].name.as_str()).collect()
    }

    fn intern_type(&mut self, name: &str) -> u32 {
        if let Some(&t) = self.type_index.get(name) {
            return t;
        }
        let t = self.types.len() as u32;
        self.types.push(TypeInfo { name: name.to_string(), declared: None, mentioned: Vec::new() });
        self.type_index.insert(name.to_string(), t);
        t
    }

    pub(crate) fn intern_constant(&mut self, name: &str) -> u32 {
        intern(&mut self.constants, &mut self.constant_index, name)
    }

    /// A bare atom without weight or period: `Pred(type, type)`.
    fn declare(&mut self, formula: Raw, at: Position) -> Result<(), MlnError> {
        let Raw::Atom { name, args } = formula else {
            return Err(MlnError::syntax(
                at,
                "a weight before the formula or a '.' after it (a hard formula)",
                "a formula with neither",
            ));
        };
        if let Some(&p) = self.predicate_index.get(&name.text) {
            let first = self.predicates[p as usize].at;
            let what = format!(
                "predicate {} (a formula needs a weight before it or a '.' after it; this reads as a declaration)",
                name.text
            );
            return Err(MlnError::at(ErrorKind::Redeclared { what, first }, name.at));
        }
        let arg_types = args.iter().map(|a| self.intern_type(&a.text)).collect();
        let p = self.predicates.len() as u32;
        self.predicates.push(Predicate { name: name.text.clone(), arg_types, at: name.at });
        self.predicate_index.insert(name.text, p);
        Ok(())
    }

    fn resolve(
        &mut self,
        raw: &Raw,
        weight: Weight,
        at: Position,
        text: String,
        checks: &mut Vec<(u32, u32, Position)>,
    ) -> Result<Formula, MlnError> {
        let mut r = Resolver { mln: self, vars: Vec::new(), scope: Vec::new(), free: Vec::new(), checks };
        let expr = r.expr(raw)?;
        let Resolver { vars, free, .. } = r;
        if let Some(v) = vars.iter().find(|v| v.ty.is_none()) {
            return Err(MlnError::at(ErrorKind::UntypedVariable { name: v.name.clone() }, v.at));
        }
        let (cnf_pos, cnf_neg) = if expr.has_quantifier() {
            (None, None)
        } else {
            (cnf(&fo_nnf(&expr, false), FO_CNF_LIMIT).ok(), cnf(&fo_nnf(&expr, true), FO_CNF_LIMIT).ok())
        };
        Ok(Formula { expr, vars, free, weight, at, text, cnf: cnf_pos, cnf_negated: cnf_neg })
    }
}

pub(crate) fn intern(names: &mut Vec<String>, index: &mut HashMap<String, u32>, name: &str) -> u32 {
    if let Some(&c) = index.get(name) {
        return c;
    }
    let c = names.len() as u32;
    names.push(name.to_string());
    index.insert(name.to_string(), c);
    c
}

struct Resolver<'a> {
    mln: &'a mut Mln,
    vars: Vec<Variable>,
    /// Quantifier scopes, innermost last: (name, slot).
    scope: Vec<(String, u32)>,
    free: Vec<u32>,
    checks: &'a mut Vec<(u32, u32, Position)>,
}

impl Resolver<'_> {
    fn variable(&mut self, name: &Name) -> u32 {
        if let Some((_, slot)) = self.scope.iter().rev().find(|(n, _)| *n == name.text) {
            return *slot;
        }
        if let Some(&slot) = self.free.iter().find(|&&s| self.vars[s as usize].name == name.text) {
            return slot;
        }
        let slot = self.new_var(name);
        self.free.push(slot);
        slot
    }

    fn new_var(&mut self, name: &Name) -> u32 {
        self.vars.push(Variable { name: name.text.clone(), ty: None, at: name.at });
        (self.vars.len() - 1) as u32
    }

    fn term(&mut self, name: &Name, ty: Option<u32>) -> Result<Term, MlnError> {
        if name.is_variable() {
            let slot = self.variable(name);
            if let Some(t) = ty {
                let v = &mut self.vars[slot as usize];
                match v.ty {
                    None => v.ty = Some(t),
                    Some(u) if u != t => {
                        let types = &self.mln.types;
                        return Err(MlnError::at(
                            ErrorKind::TypeMismatch {
                                name: name.text.clone(),
                                first: types[u as usize].name.clone(),
                                second: types[t as usize].name.clone(),
                            },
                            name.at,
                        ));
                    }
                    _ => {}
                }
            }
            Ok(Term::Var(slot))
        } else {
            let c = self.mln.intern_constant(&name.text);
            if let Some(t) = ty {
                let m = &mut self.mln.types[t as usize].mentioned;
                if !m.contains(&c) {
                    m.push(c);
                }
                self.checks.push((t, c, name.at));
            }
            Ok(Term::Const(c))
        }
    }

    fn expr(&mut self, raw: &Raw) -> Result<Expr, MlnError> {
        Ok(match raw {
            Raw::Atom { name, args } => {
                let p = resolve_predicate(self.mln, name, args.len())?;
                let types = self.mln.predicates[p as usize].arg_types.clone();
                let args = args.iter().zip(types).map(|(a, t)| self.term(a, Some(t))).collect::<Result<_, _>>()?;
                Expr::Atom { pred: p, args }
            }
            Raw::Eq { left, right, negated } => {
                let e = Expr::Eq(self.term(left, None)?, self.term(right, None)?);
                if *negated {
                    Expr::Not(Box::new(e))
                } else {
                    e
                }
            }
            Raw::Not(x) => Expr::Not(Box::new(self.expr(x)?)),
            Raw::And(v) => Expr::And(v.iter().map(|x| self.expr(x)).collect::<Result<_, _>>()?),
            Raw::Or(v) => Expr::Or(v.iter().map(|x| self.expr(x)).collect::<Result<_, _>>()?),
            Raw::Implies(a, b) => Expr::Implies(Box::new(self.expr(a)?), Box::new(self.expr(b)?)),
            Raw::Equiv(a, b) => Expr::Equiv(Box::new(self.expr(a)?), Box::new(self.expr(b)?)),
            Raw::Quant { exists, vars, body } => {
                let depth = self.scope.len();
                let mut slots = Vec::new();
                for v in vars {
                    let slot = self.new_var(v);
                    self.scope.push((v.text.clone(), slot));
                    slots.push(slot);
                }
                let body = self.expr(body)?;
                self.scope.truncate(depth);
                if *exists {
                    Expr::Exists(slots, Box::new(body))
                } else {
                    Expr::Forall(slots, Box::new(body))
                }
            }
        })
    }
}

fn resolve_predicate(mln: &Mln, name: &Name, arity: usize) -> Result<u32, MlnError> {
    let Some(&p) = mln.predicate_index.get(&name.text) else {
        return Err(MlnError::at(ErrorKind::UnknownPredicate { name: name.text.clone() }, name.at));
    };
    let expected = mln.predicates[p as usize].arg_types.len();
    if expected != arity {
        return Err(MlnError::at(ErrorKind::Arity { predicate: name.text.clone(), expected, found: arity }, name.at));
    }
    Ok(p)
}

/// What the evidence says about a ground atom.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Evidence {
    /// The atom is true.
    True,
    /// The atom is false.
    False,
    /// Soft evidence: the atom is true with this prior probability, strictly between 0 and 1.
    /// It becomes a unit clause with weight `log(p / (1 - p))`.
    Soft(f64),
}

/// A ground atom of the evidence.
#[derive(Debug, Clone)]
pub(crate) struct EvidenceAtom {
    pub pred: u32,
    pub args: Vec<String>,
    pub value: Evidence,
    pub at: Option<Position>,
}

/// An evidence database: ground atoms known true, known false, or believed with a
/// probability. Its constants join the domains of their types when grounding.
#[derive(Debug, Clone, Default)]
pub struct Database {
    pub(crate) atoms: Vec<EvidenceAtom>,
    index: HashMap<(u32, Vec<String>), usize>,
}

impl Database {
    /// An empty database.
    pub fn new() -> Self {
        Self::default()
    }

    /// Parses evidence, one atom per line: `Pred(A,B)`, `!Pred(A,B)` or `0.8 Pred(A)`.
    pub fn parse(text: &str, mln: &Mln) -> Result<Database, MlnError> {
        if text.len() > super::MAX_EVIDENCE_BYTES {
            let (len, max) = (text.len(), super::MAX_EVIDENCE_BYTES);
            return Err(super::text_too_long("evidence", len, max, "MAX_EVIDENCE_BYTES"));
        }
        Self::parse_text(text, mln).map_err(|e| e.in_text(Source::Evidence))
    }

    fn parse_text(text: &str, mln: &Mln) -> Result<Database, MlnError> {
        let mut db = Database::new();
        for line in syntax::parse_db(text)? {
            let p = resolve_predicate(mln, &line.predicate, line.args.len())?;
            if let Some(v) = line.args.iter().find(|a| a.is_variable()) {
                return Err(MlnError::at(ErrorKind::NotGround { variable: v.text.clone() }, v.at));
            }
            let value = match (line.probability, line.negated) {
                (Some(p), false) => Evidence::Soft(p),
                (Some(p), true) => Evidence::Soft(1.0 - p),
                (None, false) => Evidence::True,
                (None, true) => Evidence::False,
            };
            let args = line.args.into_iter().map(|a| a.text).collect();
            db.insert_resolved(mln, p, args, value, Some(line.predicate.at))?;
        }
        Ok(db)
    }

    /// Adds one piece of evidence. Errors if the predicate is unknown, the arity wrong, a
    /// constant empty, or the evidence contradicts what the database already says.
    pub fn insert(&mut self, mln: &Mln, predicate: &str, args: &[&str], value: Evidence) -> Result<(), MlnError> {
        let name = Name { text: predicate.to_string(), at: Position { line: 0, column: 0 } };
        let p = resolve_predicate(mln, &name, args.len()).map_err(|mut e| {
            e.position = None;
            e
        })?;
        if let Some(a) =
            args.iter().find(|a| a.is_empty() || a.contains(|c: char| c.is_whitespace() || "(),".contains(c)))
        {
            return Err(MlnError::config(format!("{a:?} is not a valid constant name")));
        }
        if let Evidence::Soft(p) = value {
            if !(p > 0.0 && p < 1.0) {
                return Err(MlnError::new(ErrorKind::BadProbability { value: p }, None));
            }
        }
        self.insert_resolved(mln, p, args.iter().map(|s| s.to_string()).collect(), value, None)
    }

    fn insert_resolved(
        &mut self,
        mln: &Mln,
        pred: u32,
        args: Vec<String>,
        value: Evidence,
        at: Option<Position>,
    ) -> Result<(), MlnError> {
        let key = (pred, args);
        if let Some(&i) = self.index.get(&key) {
            let old = &self.atoms[i];
            if old.value == value {
                return Ok(());
            }
            let atom = display_atom(&mln.predicates[pred as usize].name, &key.1);
            return Err(MlnError::new(ErrorKind::ContradictoryEvidence { atom, first: old.at }, at));
        }
        self.index.insert(key.clone(), self.atoms.len());
        self.atoms.push(EvidenceAtom { pred, args: key.1, value, at });
        Ok(())
    }

    /// Number of evidence atoms.
    pub fn len(&self) -> usize {
        self.atoms.len()
    }

    /// Whether the database holds no evidence.
    pub fn is_empty(&self) -> bool {
        self.atoms.is_empty()
    }

    /// What the database says about `predicate(args)`, if anything.
    pub fn get(&self, mln: &Mln, predicate: &str, args: &[&str]) -> Option<Evidence> {
        let p = *mln.predicate_index.get(predicate)?;
        let key = (p, args.iter().map(|s| s.to_string()).collect::<Vec<_>>());
        self.index.get(&key).map(|&i| self.atoms[i].value)
    }
}

pub(crate) fn display_atom(pred: &str, args: &[impl AsRef<str>]) -> String {
    let mut s = String::with_capacity(pred.len() + 2 + args.len() * 4);
    s.push_str(pred);
    s.push('(');
    for (i, a) in args.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        s.push_str(a.as_ref());
    }
    s.push(')');
    s
}

/// A ground atom by name: `Pred(A,B)`.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct GroundAtom {
    /// The predicate.
    pub predicate: String,
    /// The constants.
    pub args: Vec<String>,
}

impl fmt::Display for GroundAtom {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&display_atom(&self.predicate, &self.args))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn declarations_types_and_errors() {
        let kb = "unit = {A, B}\nAdj(unit,unit)\nRoom(unit)\n1.5 Adj(x,y) => Room(x)\nAdj(x,A) => Adj(A,x).\n";
        let mln = Mln::parse(kb).unwrap();
        assert_eq!(mln.predicates().len(), 2);
        assert_eq!(mln.formulas().len(), 2);
        assert_eq!(mln.formulas()[1].weight(), Weight::Hard);
        assert_eq!(mln.formulas()[0].text(), "Adj(x,y) => Room(x)");
        let e = |s: &str| Mln::parse(s).unwrap_err().to_string();
        assert_eq!(
            e("A(t)\n1 B(x)"),
            "line 2, column 3: B is not a declared predicate (declare it first, e.g. `B(type)`)"
        );
        assert_eq!(e("A(t)\n1 A(x,y)"), "line 2, column 3: A takes 1 argument, found 2");
        assert_eq!(e("A(t)\nB(s)\n1 A(x) ^ B(x)"), "line 3, column 12: x is used both as a t and as a s");
        assert_eq!(
            e("A(t)\n1 A(x) ^ y = x"),
            "line 2, column 10: cannot tell the type of variable y: it appears in no atom"
        );
        assert_eq!(e("t = {A}\nP(t)\n1 P(B)"), "line 3, column 5: constant B is not in the declared domain of type t");
        assert!(e("A(t)\nA(t)").starts_with("line 2, column 1: predicate A (a formula needs a weight"));
        assert_eq!(e("A(t)\nA(x) v A(y)"), "line 2, column 1: expected a weight before the formula or a '.' after it (a hard formula), found a formula with neither");
    }

    #[test]
    fn evidence() {
        let mln = Mln::parse("P(t)\nQ(t,t)").unwrap();
        let db = Database::parse("P(A)\n!Q(A,B)\n0.8 P(B)\n0.25 !P(C)\nP(A)", &mln).unwrap();
        assert_eq!(db.len(), 4);
        assert_eq!(db.get(&mln, "P", &["C"]), Some(Evidence::Soft(0.75)));
        let e = |s: &str| Database::parse(s, &mln).unwrap_err().to_string();
        assert_eq!(e("P(A)\n!P(A)"), "line 2, column 2: contradictory evidence for P(A) (see line 1, column 1)");
        assert_eq!(e("P(x)"), "line 1, column 3: evidence must be ground, but x is a variable (constants start with a capital letter or a digit)");
        assert_eq!(
            e("1.5 P(A)"),
            "line 1, column 1: soft evidence must be a probability strictly between 0 and 1, found 1.5"
        );
        assert_eq!(e("R(A)"), "line 1, column 1: R is not a declared predicate (declare it first, e.g. `R(type)`)");
        assert_eq!(e("Q(A)"), "line 1, column 1: Q takes 2 arguments, found 1");
        assert_eq!(e("Q(A,B"), "line 1, column 6: expected ')' after the arguments of Q, found end of input");
    }
}
