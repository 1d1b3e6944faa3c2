//! Reading settings from JSON text, the one way every config of the crate is read, and numbers
//! that survive a trip through JSON bit for bit.

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

/// Numbers that must come back to the very bits they were written from, written as JSON
/// strings of their shortest decimal form and read with Rust's correctly rounded parser:
/// serde_json's own reads about one in nine such numbers (17 significant digits) a bit off,
/// and its exact mode (`float_roundtrip`) would add 30 kB to every WebAssembly module. For
/// `#[serde(with = "crate::json::exact")]` on an `f64`; [`exact_opt`] and [`exact_map`] for
/// an `Option<f64>` and a map to four of them. Used by [`crate::floorplan::plan_input`].
pub(crate) mod exact {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(&format_args!("{v:?}"))
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        parse(&String::deserialize(d)?)
    }

    pub(super) fn parse<E: serde::de::Error>(text: &str) -> Result<f64, E> {
        text.parse().map_err(|_| E::custom(format!("{text:?} is not a number")))
    }
}

/// [`exact`] for an `Option<f64>` (`null` for none).
pub(crate) mod exact_opt {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(v: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
        match v {
            Some(v) => s.collect_str(&format_args!("{v:?}")),
            None => s.serialize_none(),
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        Option::<String>::deserialize(d)?.map(|t| super::exact::parse(&t)).transpose()
    }
}

/// [`exact`] for an optional map from ids to four numbers (`null` for none).
pub(crate) mod exact_map {
    use serde::{Deserialize, Deserializer, Serializer};
    use std::collections::BTreeMap;

    type Map = BTreeMap<u32, [f64; 4]>;

    pub fn serialize<S: Serializer>(v: &Option<Map>, s: S) -> Result<S::Ok, S::Error> {
        let text = |p: &[f64; 4]| p.map(|x| format!("{x:?}"));
        match v {
            // Entry by entry, in the map's order: collecting into another map would sort.
            Some(m) => s.collect_map(m.iter().map(|(k, p)| (*k, text(p)))),
            None => s.serialize_none(),
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Map>, D::Error> {
        let Some(m) = Option::<BTreeMap<u32, [String; 4]>>::deserialize(d)? else {
            return Ok(None);
        };
        let mut out = Map::new();
        for (k, p) in m {
            let [a, b, c, e] = p;
            out.insert(
                k,
                [
                    super::exact::parse(&a)?,
                    super::exact::parse(&b)?,
                    super::exact::parse(&c)?,
                    super::exact::parse(&e)?,
                ],
            );
        }
        Ok(Some(out))
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
        #[serde(with = "super::exact")]
        x: f64,
        #[serde(with = "super::exact_opt")]
        y: Option<f64>,
        #[serde(with = "super::exact_map")]
        m: Option<std::collections::BTreeMap<u32, [f64; 4]>>,
    }

    #[test]
    fn exact_numbers_come_back_bit_for_bit() {
        // Numbers of 17 significant digits, which serde_json's default reading gets wrong.
        let mut x = 0x9e37_79b9_7f4a_7c15_u64;
        let mut wrong = 0;
        for _ in 0..2000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = ((x >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 6.3;
            let e = E { x: v, y: Some(-v), m: Some([(7, [v, v / 3.0, 1e-300, -0.0])].into()) };
            let back: E = serde_json::from_str(&serde_json::to_string(&e).unwrap()).unwrap();
            assert_eq!(back.x.to_bits(), v.to_bits());
            assert_eq!(back.y.unwrap().to_bits(), (-v).to_bits());
            let m = back.m.unwrap()[&7];
            assert!(m.iter().zip([v, v / 3.0, 1e-300, -0.0]).all(|(a, b)| a.to_bits() == b.to_bits()));
            let plain: f64 = serde_json::from_str(&serde_json::to_string(&v).unwrap()).unwrap();
            wrong += usize::from(plain.to_bits() != v.to_bits());
        }
        // The reason for the module: the plain trip changes some of them.
        assert!(wrong > 0, "serde_json read every number back exactly; `exact` may be unneeded");
        let none = E { x: 0.5, y: None, m: None };
        assert_eq!(serde_json::from_str::<E>(&serde_json::to_string(&none).unwrap()).unwrap(), none);
        assert!(serde_json::from_str::<E>(r#"{"x": "nope", "y": null, "m": null}"#).is_err());
    }
}
