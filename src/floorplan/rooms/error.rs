//! The room layer's one error type.
//!
//! Every way the room layer can fail (settings a person wrote, room or frontier rules that do
//! not parse or cannot be grounded, a training world that does not fit its truth) is a [`RoomError`]
//! whose message says what failed and how to put it right, with the cause behind it as its
//! [`source`](std::error::Error::source) where there is one. Its kind is private, as
//! `regex-automata`'s errors keep theirs: callers print it or pass it on, and new kinds can
//! come without breaking them.

use crate::mln::MlnError;

/// Why the room layer could not find the rooms, read its settings or make a training world.
#[derive(Debug, Clone, PartialEq)]
pub struct RoomError {
    kind: Kind,
}

#[derive(Debug, Clone, PartialEq)]
enum Kind {
    /// The settings (`RoomConfig` as JSON) are not valid; the message says which.
    Settings(String),
    /// The room rules, or the indoor rules that type the rooms, failed: in `step`.
    Rules { step: &'static str, cause: MlnError },
    /// The frontier rules that weigh the placeholders failed: in `step`.
    Frontier { step: &'static str, cause: MlnError },
    /// A training world cannot be made; the message says why.
    Training(String),
}

impl RoomError {
    pub(crate) fn settings(message: impl Into<String>) -> RoomError {
        RoomError { kind: Kind::Settings(message.into()) }
    }

    pub(crate) fn rules(step: &'static str, cause: MlnError) -> RoomError {
        RoomError { kind: Kind::Rules { step, cause } }
    }

    pub(crate) fn frontier(step: &'static str, cause: MlnError) -> RoomError {
        RoomError { kind: Kind::Frontier { step, cause } }
    }

    pub(crate) fn training(message: impl Into<String>) -> RoomError {
        RoomError { kind: Kind::Training(message.into()) }
    }
}

impl std::fmt::Display for RoomError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.kind {
            Kind::Settings(m) => write!(f, "room settings: {m}"),
            Kind::Rules { step, cause } => write!(f, "room rules, {step}: {cause}"),
            Kind::Frontier { step, cause } => write!(f, "frontier rules (knowledge.frontier_kb), {step}: {cause}"),
            Kind::Training(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for RoomError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match &self.kind {
            Kind::Rules { cause, .. } | Kind::Frontier { cause, .. } => Some(cause),
            _ => None,
        }
    }
}
