//! Reading settings from JSON text, the one way every config of the crate is read.

use serde::de::DeserializeOwned;

/// Parses a JSON object of settings over `T`'s defaults (with `#[serde(default)]`, fields it
/// leaves out keep theirs). Blank text is the defaults; anything but an object is refused with
/// `example` as the hint. The error is serde's message with its line and column, unprefixed.
pub(crate) fn settings<T: DeserializeOwned + Default>(text: &str, example: &str) -> Result<T, String> {
    if text.trim().is_empty() {
        return Ok(T::default());
    }
    let value: serde_json::Value = serde_json::from_str(text).map_err(|e| e.to_string())?;
    if !value.is_object() {
        return Err(format!("expected a JSON object such as {example}"));
    }
    // From the text rather than the value, so that a wrong field keeps its line and column.
    serde_json::from_str(text).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::settings;
    use serde::Deserialize;

    #[derive(Debug, Default, PartialEq, Deserialize)]
    #[serde(default, deny_unknown_fields)]
    struct S {
        a: u32,
        b: u32,
    }

    #[test]
    fn blank_is_default_fields_go_over_defaults_and_the_rest_is_refused() {
        assert_eq!(settings::<S>("  ", "{}"), Ok(S::default()));
        assert_eq!(settings::<S>(r#"{"b": 2}"#, "{}"), Ok(S { a: 0, b: 2 }));
        assert_eq!(settings::<S>("[1]", r#"{"a": 1}"#), Err(r#"expected a JSON object such as {"a": 1}"#.into()));
        let e = settings::<S>("{\n\"c\": 1}", "{}").unwrap_err();
        assert!(e.contains("unknown field `c`") && e.contains("line 2"), "{e}");
        assert!(settings::<S>("nope", "{}").unwrap_err().contains("expected"));
    }
}
