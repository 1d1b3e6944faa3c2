//! Errors from parsing knowledge bases and evidence, grounding and inference.
//!
//! Every error that comes from a text carries the line and column it refers to, and says what
//! was expected: a knowledge base is written by hand, and "syntax error" teaches nothing.

use std::fmt;

/// A place in a knowledge base or evidence text: 1-based line and column (in characters).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Position {
    /// Line, from 1.
    pub line: u32,
    /// Column, from 1, counted in characters.
    pub column: u32,
}

impl fmt::Display for Position {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}, column {}", self.line, self.column)
    }
}

/// What went wrong; see [`MlnError`] for where.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ErrorKind {
    /// The text does not follow the grammar.
    Syntax {
        /// What the parser could have accepted here.
        expected: String,
        /// What it found instead, quoted, or "end of line".
        found: String,
    },
    /// A formula or evidence atom names a predicate the knowledge base does not declare.
    UnknownPredicate {
        /// The name.
        name: String,
    },
    /// An atom has the wrong number of arguments.
    Arity {
        /// The predicate.
        predicate: String,
        /// Arguments in its declaration.
        expected: usize,
        /// Arguments found.
        found: usize,
    },
    /// A predicate or a type's domain is declared twice.
    Redeclared {
        /// What, e.g. "predicate Adj".
        what: String,
        /// Where the first declaration is.
        first: Position,
    },
    /// A weight is not a finite number.
    BadWeight {
        /// Why.
        message: String,
    },
    /// A variable or constant is used with two different types.
    TypeMismatch {
        /// The variable or constant.
        name: String,
        /// The type of its first use.
        first: String,
        /// The conflicting type.
        second: String,
    },
    /// A variable appears in no atom, so its type (and the constants it ranges over) is unknown.
    UntypedVariable {
        /// The variable.
        name: String,
    },
    /// A constant is not in the declared (closed) domain of its type.
    UnknownConstant {
        /// The constant.
        constant: String,
        /// The type.
        type_name: String,
    },
    /// A domain was given for a type no predicate uses.
    UnknownType {
        /// The type name.
        name: String,
    },
    /// The evidence says both that an atom is true and that it is false (or gives it twice
    /// with different probabilities).
    ContradictoryEvidence {
        /// The ground atom, e.g. `Adj(A,B)`.
        atom: String,
        /// Where the first, conflicting, statement is (if it came from a text).
        first: Option<Position>,
    },
    /// Soft evidence must be a probability strictly between 0 and 1.
    BadProbability {
        /// The value given.
        value: f64,
    },
    /// Evidence must be ground, but an argument is a variable.
    NotGround {
        /// The variable.
        variable: String,
    },
    /// A configuration value is out of range or inconsistent.
    InvalidConfig {
        /// Why.
        message: String,
    },
    /// The ground network would exceed a configured size limit.
    TooLarge {
        /// What was counted: "ground atoms", "ground clauses", "groundings", ...
        what: &'static str,
        /// The limit in force.
        limit: u64,
    },
    /// The hard formulas cannot all hold given the evidence.
    Unsatisfiable {
        /// Which formula failed, and for which constants.
        message: String,
    },
    /// Exact inference was asked for a network too large to enumerate.
    TooManyUnknownAtoms {
        /// Unknown atoms in the largest connected part of the network.
        atoms: usize,
        /// The limit in force.
        limit: usize,
    },
    /// WalkSAT found no world satisfying the hard formulas (they may be contradictory).
    NoSatisfyingWorld {
        /// Flips tried.
        flips: u64,
    },
}

/// Which text an error position refers to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// The knowledge base given to [`super::Mln::parse`].
    KnowledgeBase,
    /// The evidence given to [`super::Database::parse`].
    Evidence,
}

/// An error from the Markov logic engine, with the position in the text it refers to.
///
/// Displays as `line 3, column 17: expected ')' after the arguments of Adj, found '^'`.
#[derive(Debug, Clone, PartialEq)]
pub struct MlnError {
    /// What went wrong.
    pub kind: ErrorKind,
    /// Where, when the error concerns a knowledge base or evidence text.
    pub position: Option<Position>,
    /// Which text `position` is in (set whenever `position` is).
    pub source: Option<Source>,
}

/// An [`MlnError`] as a rules editor shows it: 1-based line and column (0 when the error has
/// no place in the text) and the message without the position. Serialises as
/// `{"line", "column", "message"}`, what the wasm `checkRules` and `tabletopCheckRules` return.
///
/// ```
/// use ksmcmc::mln::{Mln, RuleError};
/// let e = Mln::parse("Room(unit)\n1 Room(x) =>").unwrap_err();
/// let r = RuleError::from(&e);
/// assert_eq!((r.line, r.column), (2, 13));
/// assert!(!r.message.contains("line 2"), "{}", r.message);
/// ```
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct RuleError {
    /// Line, from 1 (0: no position).
    pub line: u32,
    /// Column, from 1, in characters (0: no position).
    pub column: u32,
    /// What went wrong.
    pub message: String,
}

impl From<&MlnError> for RuleError {
    fn from(e: &MlnError) -> Self {
        let (line, column) = e.position.map_or((0, 0), |p| (p.line, p.column));
        RuleError { line, column, message: e.kind.to_string() }
    }
}

impl MlnError {
    pub(crate) fn new(kind: ErrorKind, position: Option<Position>) -> Self {
        MlnError { kind, position, source: None }
    }

    pub(crate) fn at(kind: ErrorKind, position: Position) -> Self {
        MlnError { kind, position: Some(position), source: None }
    }

    /// Tags a positioned error with the text it came from.
    pub(crate) fn in_text(mut self, source: Source) -> Self {
        if self.position.is_some() {
            self.source = Some(source);
        }
        self
    }

    pub(crate) fn syntax(at: Position, expected: impl Into<String>, found: impl Into<String>) -> Self {
        MlnError::at(ErrorKind::Syntax { expected: expected.into(), found: found.into() }, at)
    }

    pub(crate) fn config(message: impl Into<String>) -> Self {
        MlnError::new(ErrorKind::InvalidConfig { message: message.into() }, None)
    }

    pub(crate) fn too_large(what: &'static str, limit: u64) -> Self {
        MlnError::new(ErrorKind::TooLarge { what, limit }, None)
    }
}

impl fmt::Display for ErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ErrorKind::Syntax { expected, found } => write!(f, "expected {expected}, found {found}"),
            ErrorKind::UnknownPredicate { name } => {
                write!(f, "{name} is not a declared predicate (declare it first, e.g. `{name}(type)`)")
            }
            ErrorKind::Arity { predicate, expected, found } => {
                let s = if *expected == 1 { "" } else { "s" };
                write!(f, "{predicate} takes {expected} argument{s}, found {found}")
            }
            ErrorKind::Redeclared { what, first } => write!(f, "{what} is already declared at {first}"),
            ErrorKind::BadWeight { message } => write!(f, "bad weight: {message}"),
            ErrorKind::TypeMismatch { name, first, second } => {
                write!(f, "{name} is used both as a {first} and as a {second}")
            }
            ErrorKind::UntypedVariable { name } => {
                write!(f, "cannot tell the type of variable {name}: it appears in no atom")
            }
            ErrorKind::UnknownConstant { constant, type_name } => {
                write!(f, "constant {constant} is not in the declared domain of type {type_name}")
            }
            ErrorKind::UnknownType { name } => write!(f, "unknown type {name}: no predicate has an argument of it"),
            ErrorKind::ContradictoryEvidence { atom, first } => match first {
                Some(p) => write!(f, "contradictory evidence for {atom} (see {p})"),
                None => write!(f, "contradictory evidence for {atom}"),
            },
            ErrorKind::BadProbability { value } => {
                write!(f, "soft evidence must be a probability strictly between 0 and 1, found {value}")
            }
            ErrorKind::NotGround { variable } => write!(
                f,
                "evidence must be ground, but {variable} is a variable (constants start with a capital letter or a digit)"
            ),
            ErrorKind::InvalidConfig { message } => f.write_str(message),
            ErrorKind::TooLarge { what, limit } => {
                write!(f, "the ground network would have more than {limit} {what} (raise the limit or shrink the domains)")
            }
            ErrorKind::Unsatisfiable { message } => f.write_str(message),
            ErrorKind::TooManyUnknownAtoms { atoms, limit } => write!(
                f,
                "exact inference enumerates 2^n worlds, and a connected part of this network has {atoms} unknown atoms, \
                 more than the limit of {limit}; use MC-SAT or Gibbs sampling"
            ),
            ErrorKind::NoSatisfyingWorld { flips } => {
                write!(f, "WalkSAT found no world satisfying all hard formulas in {flips} flips; are they contradictory?")
            }
        }
    }
}

impl fmt::Display for MlnError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.position {
            Some(p) => write!(f, "{p}: {}", self.kind),
            None => write!(f, "{}", self.kind),
        }
    }
}

impl std::error::Error for MlnError {}

/// A method's name that [`Method`](super::Method) or [`LearnMethod`](super::LearnMethod) does
/// not know (`"mcsat".parse::<Method>()`); it says which names it knows.
///
/// ```
/// use ksmcmc::mln::{LearnMethod, Method};
/// let e = "annealing".parse::<Method>().unwrap_err();
/// assert_eq!(e.name(), "annealing");
/// assert_eq!(e.to_string(), r#"unknown inference method "annealing" (auto, exact, enumerate, mcsat or gibbs)"#);
/// assert!("em".parse::<LearnMethod>().unwrap_err().to_string().contains("(pll or discriminative)"));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownMethod {
    name: String,
    /// `inference method` or `learning method`.
    what: &'static str,
    /// The names known, as a person reads them.
    known: &'static str,
}

impl UnknownMethod {
    pub(crate) fn new(name: &str, what: &'static str, known: &'static str) -> Self {
        UnknownMethod { name: name.to_owned(), what, known }
    }

    /// The name given.
    pub fn name(&self) -> &str {
        &self.name
    }
}

impl fmt::Display for UnknownMethod {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "unknown {} {:?} ({})", self.what, self.name, self.known)
    }
}

impl std::error::Error for UnknownMethod {}
