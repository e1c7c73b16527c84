//! Structure checks made while a file is read, that a value's range
//! cannot express, and the bound the schema's positions share.
//!
//! Ranges of numbers are not checked here: they are declared once on each
//! field (`#[schemars(range(..))]`) and checked against the schema made
//! from the types ([`super::schema`]).

use serde::de::{Deserialize, Deserializer, Error};

/// Largest distance from the origin a position may have on any axis, m:
/// the sparring room is a few metres across; this leaves room for props
/// thrown far, not for typos such as 1e6.
pub const MAX_POSITION: f64 = 100.0;

/// A map whose keys must each appear once (serde's maps keep the last of
/// a repeated key silently; in a bindings file that hides a mistake).
pub fn unique_keys<'de, D, K, V>(d: D) -> Result<std::collections::BTreeMap<K, V>, D::Error>
where
    D: Deserializer<'de>,
    K: Deserialize<'de> + Ord + std::fmt::Debug,
    V: Deserialize<'de>,
{
    struct Visit<K, V>(std::marker::PhantomData<(K, V)>);
    impl<'de, K, V> serde::de::Visitor<'de> for Visit<K, V>
    where
        K: Deserialize<'de> + Ord + std::fmt::Debug,
        V: Deserialize<'de>,
    {
        type Value = std::collections::BTreeMap<K, V>;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("a map")
        }
        fn visit_map<A: serde::de::MapAccess<'de>>(
            self,
            mut m: A,
        ) -> Result<Self::Value, A::Error> {
            let mut out = std::collections::BTreeMap::new();
            while let Some((k, v)) = m.next_entry::<K, V>()? {
                if out.contains_key(&k) {
                    return Err(A::Error::custom(format!("{k:?} appears twice")));
                }
                out.insert(k, v);
            }
            Ok(out)
        }
    }
    d.deserialize_map(Visit(std::marker::PhantomData))
}
