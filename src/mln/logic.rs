//! First-order formulas after name resolution, and their conversion to clausal form.
//!
//! Grounding wants conjunctive normal form: a ground formula is a conjunction of clauses, each
//! a disjunction of literals, because that is what the satisfiability-based samplers (WalkSAT,
//! SampleSAT) work on. Negations are pushed to the atoms while walking the tree (negation
//! normal form), then disjunction is distributed over conjunction. Distribution can grow
//! exponentially, so it stops at a limit and reports it.

/// An argument of an atom: a variable (slot in its formula) or a constant (global id).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Term {
    Var(u32),
    Const(u32),
}

/// A resolved first-order formula.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Expr {
    Atom { pred: u32, args: Vec<Term> },
    Eq(Term, Term),
    Not(Box<Expr>),
    And(Vec<Expr>),
    Or(Vec<Expr>),
    Implies(Box<Expr>, Box<Expr>),
    Equiv(Box<Expr>, Box<Expr>),
    Exists(Vec<u32>, Box<Expr>),
    Forall(Vec<u32>, Box<Expr>),
}

impl Expr {
    pub fn has_quantifier(&self) -> bool {
        match self {
            Expr::Atom { .. } | Expr::Eq(..) => false,
            Expr::Not(e) => e.has_quantifier(),
            Expr::And(v) | Expr::Or(v) => v.iter().any(Expr::has_quantifier),
            Expr::Implies(a, b) | Expr::Equiv(a, b) => a.has_quantifier() || b.has_quantifier(),
            Expr::Exists(..) | Expr::Forall(..) => true,
        }
    }
}

/// A first-order literal of a quantifier-free formula.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct FoLit {
    pub negated: bool,
    pub kind: FoKind,
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) enum FoKind {
    Atom { pred: u32, args: Vec<Term> },
    Eq(Term, Term),
}

/// Negation normal form over some literal type: only literals are negated.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Nnf<L> {
    True,
    False,
    Lit(L),
    And(Vec<Nnf<L>>),
    Or(Vec<Nnf<L>>),
}

impl<L> Nnf<L> {
    /// A conjunction, simplified: `False` absorbs, `True` vanishes.
    pub fn and(items: Vec<Nnf<L>>) -> Nnf<L> {
        let mut out = Vec::with_capacity(items.len());
        for i in items {
            match i {
                Nnf::False => return Nnf::False,
                Nnf::True => {}
                Nnf::And(v) => out.extend(v),
                x => out.push(x),
            }
        }
        match out.len() {
            0 => Nnf::True,
            1 => out.pop().unwrap(),
            _ => Nnf::And(out),
        }
    }

    /// A disjunction, simplified: `True` absorbs, `False` vanishes.
    pub fn or(items: Vec<Nnf<L>>) -> Nnf<L> {
        let mut out = Vec::with_capacity(items.len());
        for i in items {
            match i {
                Nnf::True => return Nnf::True,
                Nnf::False => {}
                Nnf::Or(v) => out.extend(v),
                x => out.push(x),
            }
        }
        match out.len() {
            0 => Nnf::False,
            1 => out.pop().unwrap(),
            _ => Nnf::Or(out),
        }
    }
}

/// A conjunction of clauses. No clauses: true. An empty clause: false.
pub(crate) type Cnf<L> = Vec<Vec<L>>;

/// The clause count would pass the limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct CnfTooLarge;

/// Converts to conjunctive normal form, giving up past `limit` clauses.
pub(crate) fn cnf<L: Clone>(n: &Nnf<L>, limit: usize) -> Result<Cnf<L>, CnfTooLarge> {
    match n {
        Nnf::True => Ok(Vec::new()),
        Nnf::False => Ok(vec![Vec::new()]),
        Nnf::Lit(l) => Ok(vec![vec![l.clone()]]),
        Nnf::And(items) => {
            let mut out = Vec::new();
            for i in items {
                out.extend(cnf(i, limit)?);
                if out.len() > limit {
                    return Err(CnfTooLarge);
                }
            }
            Ok(out)
        }
        Nnf::Or(items) => {
            let mut out: Cnf<L> = vec![Vec::new()];
            for i in items {
                let c = cnf(i, limit)?;
                if c.len().saturating_mul(out.len()) > limit {
                    return Err(CnfTooLarge);
                }
                let mut next = Vec::with_capacity(c.len() * out.len());
                for a in &out {
                    for b in &c {
                        let mut clause = a.clone();
                        clause.extend(b.iter().cloned());
                        next.push(clause);
                    }
                }
                out = next;
            }
            Ok(out)
        }
    }
}

/// Negation normal form of a quantifier-free formula at the first-order level, negated if
/// `negate`. Equalities between two constants are decided here.
pub(crate) fn fo_nnf(e: &Expr, negate: bool) -> Nnf<FoLit> {
    match e {
        Expr::Atom { pred, args } => {
            Nnf::Lit(FoLit { negated: negate, kind: FoKind::Atom { pred: *pred, args: args.clone() } })
        }
        Expr::Eq(a, b) => match (a, b) {
            (Term::Const(x), Term::Const(y)) => {
                if (x == y) != negate {
                    Nnf::True
                } else {
                    Nnf::False
                }
            }
            _ => Nnf::Lit(FoLit { negated: negate, kind: FoKind::Eq(*a, *b) }),
        },
        Expr::Not(x) => fo_nnf(x, !negate),
        Expr::And(v) => {
            let items = v.iter().map(|x| fo_nnf(x, negate)).collect();
            if negate {
                Nnf::or(items)
            } else {
                Nnf::and(items)
            }
        }
        Expr::Or(v) => {
            let items = v.iter().map(|x| fo_nnf(x, negate)).collect();
            if negate {
                Nnf::and(items)
            } else {
                Nnf::or(items)
            }
        }
        Expr::Implies(a, b) => {
            // a => b  ==  !a v b;  !(a => b)  ==  a ^ !b
            if negate {
                Nnf::and(vec![fo_nnf(a, false), fo_nnf(b, true)])
            } else {
                Nnf::or(vec![fo_nnf(a, true), fo_nnf(b, false)])
            }
        }
        Expr::Equiv(a, b) => {
            // a <=> b  ==  (!a v b) ^ (a v !b);  !(a <=> b)  ==  (a v b) ^ (!a v !b)
            Nnf::and(vec![
                Nnf::or(vec![fo_nnf(a, !negate), fo_nnf(b, false)]),
                Nnf::or(vec![fo_nnf(a, negate), fo_nnf(b, true)]),
            ])
        }
        Expr::Exists(..) | Expr::Forall(..) => unreachable!("quantified formulas are grounded one grounding at a time"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distributes_and_limits() {
        let l = |i: u32| Nnf::Lit(i);
        // (1 ^ 2) v (3 ^ 4) = (1 v 3)(1 v 4)(2 v 3)(2 v 4)
        let n = Nnf::or(vec![Nnf::and(vec![l(1), l(2)]), Nnf::and(vec![l(3), l(4)])]);
        assert_eq!(cnf(&n, 100).unwrap(), vec![vec![1, 3], vec![1, 4], vec![2, 3], vec![2, 4]]);
        assert_eq!(cnf(&n, 3), Err(CnfTooLarge));
        assert_eq!(cnf(&Nnf::<u32>::True, 1).unwrap(), Vec::<Vec<u32>>::new());
        assert_eq!(cnf(&Nnf::<u32>::False, 1).unwrap(), vec![Vec::<u32>::new()]);
    }
}
