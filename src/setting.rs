//! One error for a setting out of its range, which every configuration's `validate` returns.
//!
//! A configuration is checked field by field before a chain starts, and the person who wrote it
//! needs to know which field to change and to what: "posterior.temperature -1 must be a
//! positive number". A program needs the same as data, to point at the field in a form:
//! [`InvalidSetting::field`] is the field's path in the configuration's JSON, each section
//! adding its name in front. Where a setting is text that must parse (a rule set), the parse
//! error is the [`source`](std::error::Error::source).
//!
//! One type, written once, also keeps the WebAssembly modules small: each check passes a field
//! name, a value and a phrase, and only [`InvalidSetting`]'s `Display` formats them.

use crate::mln::MlnError;
use std::borrow::Cow;
use std::error::Error;
use std::fmt;

/// A setting out of its range: which field, the value given (when it is one number) and what
/// the value must be.
///
/// ```
/// use ksmcmc::floorplan::{ChainConfig, ChainError};
///
/// let mut c = ChainConfig::default();
/// c.posterior.temperature = -1.0;
/// let Err(ChainError::Config(e)) = c.validate() else { panic!("accepted") };
/// assert_eq!((e.field(), e.value()), ("posterior.temperature", Some(-1.0)));
/// assert_eq!(e.to_string(), "posterior.temperature -1 must be a positive number");
/// ```
#[derive(Clone, PartialEq)]
pub struct InvalidSetting(Box<Setting>);

// Boxed, so that a `Result<(), InvalidSetting>` is one pointer: every check's `?` then passes
// a pointer on, not the whole record (which cost the mapper module 120 bytes gzipped).
#[derive(Clone, PartialEq)]
struct Setting {
    field: Cow<'static, str>,
    value: Option<f64>,
    expected: &'static str,
    // The rule sets are the only settings that parse, so the cause is a Markov logic error: a
    // `dyn Error` here would carry every cause's `Debug` into the mapper module (1.4 kB).
    source: Option<MlnError>,
}

impl InvalidSetting {
    /// `field` (with its `value` when it is one number) is not `expected`.
    pub(crate) fn new(field: &'static str, value: Option<f64>, expected: &'static str) -> Self {
        InvalidSetting(Box::new(Setting { field: Cow::Borrowed(field), value, expected, source: None }))
    }

    /// `field` is text that does not parse: `cause` says where and why.
    pub(crate) fn unreadable(field: &'static str, expected: &'static str, cause: MlnError) -> Self {
        let field = Cow::Borrowed(field);
        InvalidSetting(Box::new(Setting { field, value: None, expected, source: Some(cause) }))
    }

    /// The same error seen from the section holding the field: `kernels` makes `max_units`
    /// `kernels.max_units`.
    pub(crate) fn within(mut self, section: &str) -> Self {
        self.0.field = Cow::Owned(format!("{section}.{}", self.0.field));
        self
    }

    /// The field's path in the configuration's JSON, sections joined by dots.
    pub fn field(&self) -> &str {
        &self.0.field
    }

    /// The value given, when the field is one number.
    pub fn value(&self) -> Option<f64> {
        self.0.value
    }

    /// What the value must be, as a phrase: "a positive number", "in (0, 1]".
    pub fn expected(&self) -> &str {
        self.0.expected
    }
}

/// `Ok` when `ok`; otherwise `field`, whose value is `value`, must be `expected`. Never inlined:
/// a copy of the error's construction at each of the checks cost the mapper module 3 kB.
#[inline(never)]
pub(crate) fn check(ok: bool, field: &'static str, value: f64, expected: &'static str) -> Result<(), InvalidSetting> {
    match ok {
        true => Ok(()),
        false => Err(InvalidSetting::new(field, Some(value), expected)),
    }
}

/// `Ok` when `ok`; otherwise `fields` (no one number: several fields, or a list) must be
/// `expected`.
#[inline(never)]
pub(crate) fn require(ok: bool, fields: &'static str, expected: &'static str) -> Result<(), InvalidSetting> {
    match ok {
        true => Ok(()),
        false => Err(InvalidSetting::new(fields, None, expected)),
    }
}

/// As its message: the cause's own `Debug` would only repeat it.
impl fmt::Debug for InvalidSetting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "InvalidSetting(\"{self}\")")
    }
}

impl fmt::Display for InvalidSetting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = &self.0;
        match s.value {
            Some(v) => write!(f, "{} {v} must be {}", s.field, s.expected),
            None => write!(f, "{} must be {}", s.field, s.expected),
        }?;
        match &s.source {
            Some(cause) => write!(f, ": {cause}"),
            None => Ok(()),
        }
    }
}

impl Error for InvalidSetting {
    fn source(&self) -> Option<&(dyn Error + 'static)> {
        self.0.source.as_ref().map(|e| e as &(dyn Error + 'static))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_the_field_its_value_and_what_it_must_be() {
        let e = check(false, "temperature", -1.0, "a positive number").unwrap_err().within("posterior");
        assert_eq!(e.to_string(), "posterior.temperature -1 must be a positive number");
        assert_eq!((e.field(), e.value(), e.expected()), ("posterior.temperature", Some(-1.0), "a positive number"));
        assert!(e.source().is_none());
        assert!(check(true, "temperature", 1.0, "a positive number").is_ok());
        let e = require(false, "every, samples", "at least 1").unwrap_err();
        assert_eq!(e.to_string(), "every, samples must be at least 1");
    }

    #[test]
    fn text_that_does_not_parse_keeps_its_parse_error_as_the_source() {
        let cause = crate::mln::Mln::parse("Room(x) =>").unwrap_err();
        let e = InvalidSetting::unreadable("room_kb", "rules that parse", cause.clone()).within("knowledge");
        assert_eq!(e.clone(), e);
        assert_eq!(e.to_string(), format!("knowledge.room_kb must be rules that parse: {cause}"));
        assert_eq!(e.source().map(|s| s.to_string()), Some(cause.to_string()));
    }
}
