//! Reading settings from JSON text, the one way every config of the crate is read, and numbers
//! that read back to the very bits they were written from.
//!
//! serde_json writes an `f64` in its shortest exact form, but its reader is fast rather than
//! exact: it reads about one in nine numbers of 17 significant digits a bit off, and then a
//! world's JSON does not read back to the same text (`fuzz/regressions/world_json`: a room area
//! of 3.8e122), nor would the browser's plan module find the rooms the chain found
//! ([`crate::floorplan::plan_input`]: the frame's angle). serde_json's exact reader (its
//! `float_roundtrip` feature) would add 12 kB gzipped to every WebAssembly module, which would
//! put the live mapper's module over its 500 kB (BENCHMARKS.md). So the numbers that must come
//! back exactly are read through [`exact`] and its kin: serde_json hands over the number's text
//! as it found it (its `raw_value` feature) and Rust's correctly rounded parser reads it. The
//! JSON is unchanged (numbers stay numbers); only serde_json's deserializers can read these
//! fields.

use serde::de::DeserializeOwned;
use serde::{Deserialize, Deserializer};
use serde_json::value::RawValue;
use std::collections::BTreeMap;

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

/// A JSON number read exactly: `#[serde(deserialize_with = "crate::json::exact")]` on an
/// `f64` (see the module docs).
pub(crate) fn exact<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    number(&Box::<RawValue>::deserialize(d)?)
}

/// [`exact`] for an `Option<f64>` (`null` for none).
pub(crate) fn exact_opt<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
    let raw = Box::<RawValue>::deserialize(d)?;
    if raw.get() == "null" {
        return Ok(None);
    }
    number(&raw).map(Some)
}

/// [`exact`] for an optional map from ids to four numbers (`null` for none).
pub(crate) fn exact_map<'de, D: Deserializer<'de>>(d: D) -> Result<Option<BTreeMap<u32, [f64; 4]>>, D::Error> {
    let Some(m) = Option::<BTreeMap<u32, [Box<RawValue>; 4]>>::deserialize(d)? else {
        return Ok(None);
    };
    let mut out = BTreeMap::new();
    for (k, [a, b, c, e]) in m {
        out.insert(k, [number(&a)?, number(&b)?, number(&c)?, number(&e)?]);
    }
    Ok(Some(out))
}

/// The number a raw JSON value spells, correctly rounded; an error for any other value and for
/// a number beyond `f64` (as serde_json's own reader refuses it).
fn number<E: serde::de::Error>(raw: &RawValue) -> Result<f64, E> {
    let text = raw.get();
    let is_number = text.starts_with(|c: char| c == '-' || c.is_ascii_digit());
    match text.parse::<f64>() {
        Ok(x) if is_number && x.is_finite() => Ok(x),
        Ok(_) if is_number => Err(E::custom(format!("number out of range: {text}"))),
        _ => Err(E::invalid_type(serde::de::Unexpected::Other(text), &"a number")),
    }
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

    #[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    struct E {
        #[serde(deserialize_with = "super::exact")]
        x: f64,
        #[serde(deserialize_with = "super::exact_opt")]
        y: Option<f64>,
        #[serde(deserialize_with = "super::exact_map")]
        m: Option<std::collections::BTreeMap<u32, [f64; 4]>>,
    }

    #[test]
    fn exact_numbers_come_back_bit_for_bit() {
        // Numbers of 17 significant digits, which serde_json's own reader gets wrong one time
        // in nine, and huge and tiny ones.
        let mut x = 0x9e37_79b9_7f4a_7c15_u64;
        let mut numbers = vec![3.777_777_777_777_778e122, 1e-300, -0.0, f64::MAX, f64::MIN_POSITIVE, 5.0];
        for _ in 0..2000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            numbers.push(((x >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 6.3);
        }
        let mut wrong = 0;
        for v in numbers {
            let e = E { x: v, y: Some(-v), m: Some([(7, [v, v / 3.0, 1e-300, -0.0])].into()) };
            let text = serde_json::to_string(&e).unwrap();
            let back: E = serde_json::from_str(&text).unwrap();
            assert_eq!(back.x.to_bits(), v.to_bits(), "{v:?} read back as {:?}", back.x);
            assert_eq!(back.y.unwrap().to_bits(), (-v).to_bits());
            let m = back.m.unwrap()[&7];
            assert!(m.iter().zip([v, v / 3.0, 1e-300, -0.0]).all(|(a, b)| a.to_bits() == b.to_bits()));
            let plain: f64 = serde_json::from_str(&serde_json::to_string(&v).unwrap()).unwrap();
            wrong += usize::from(plain.to_bits() != v.to_bits());
        }
        // The reason for `exact`: serde_json's own reader changes some of them.
        assert!(wrong > 0, "serde_json read every number back exactly; `exact` may be unneeded");
    }

    #[test]
    fn exact_numbers_are_numbers() {
        let read = |t: &str| serde_json::from_str::<E>(t).map_err(|e| e.to_string());
        assert_eq!(read(r#"{"x": 1, "y": null, "m": null}"#), Ok(E { x: 1.0, y: None, m: None }));
        assert_eq!(read(r#"{"x": -2.5E-3, "y": 1e+2, "m": null}"#), Ok(E { x: -2.5e-3, y: Some(100.0), m: None }));
        for bad in [r#""1.5""#, "null", "true", "[1]", "1e400", "-1e999"] {
            let e = read(&format!(r#"{{"x": {bad}, "y": null, "m": null}}"#)).unwrap_err();
            assert!(e.contains("line 1"), "{bad}: {e}");
        }
        assert!(read(r#"{"x": 1, "y": "2", "m": null}"#).unwrap_err().contains("a number"));
        assert!(read(r#"{"x": 1, "y": null, "m": {"1": [1, 2, 3, "4"]}}"#).unwrap_err().contains("a number"));
        // Also from a `serde_json::Value`.
        let v = serde_json::json!({"x": 0.1, "y": 0.2, "m": {"3": [1.0, 2.0, 3.0, 4.0]}});
        let e: E = serde_json::from_value(v).unwrap();
        assert_eq!((e.x, e.y, e.m.unwrap()[&3]), (0.1, Some(0.2), [1.0, 2.0, 3.0, 4.0]));
    }
}
