//! Validating deserialisers for numeric fields of scene and gains files.
//!
//! Use them as `#[serde(deserialize_with = "crate::util::check::non_negative")]` on
//! plain `f64` fields. Because the check runs while the field itself is being
//! read, the RON parser reports the error at that field's line and column and
//! `serde_path_to_error` names the field: a user sees
//! `scenes/x.ron:12:14: vh.gains.neck.kp: must be >= 0, got -3`.

use serde::de::{Deserialize, Deserializer, Error};

fn read<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    let v = f64::deserialize(d)?;
    if !v.is_finite() {
        return Err(D::Error::custom(format!(
            "must be a finite number, got {v}"
        )));
    }
    Ok(v)
}

/// Any finite number (rejects NaN and infinities).
pub fn finite<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    read(d)
}

/// A finite number `>= 0`.
pub fn non_negative<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    let v = read(d)?;
    if v < 0.0 {
        return Err(D::Error::custom(format!("must be >= 0, got {v}")));
    }
    Ok(v)
}

/// A finite number `> 0`.
pub fn positive<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    let v = read(d)?;
    if v <= 0.0 {
        return Err(D::Error::custom(format!("must be > 0, got {v}")));
    }
    Ok(v)
}

/// A finite number in `[0, 1]` (fractions, probabilities, intensities).
pub fn unit_interval<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    in_range(d, 0.0, 1.0)
}

/// A finite number in `[lo, hi]`; build field-specific checks on it.
pub fn in_range<'de, D: Deserializer<'de>>(d: D, lo: f64, hi: f64) -> Result<f64, D::Error> {
    let v = read(d)?;
    if !(lo..=hi).contains(&v) {
        return Err(D::Error::custom(format!(
            "must be in [{lo}, {hi}], got {v}"
        )));
    }
    Ok(v)
}

/// Field checks with fixed bounds, one function per line:
/// `ranged_fields! { latency: 0.0, 1.0; }` defines
/// `fn latency(d) -> Result<f64, _>` checking [`in_range`] `[0, 1]`, for
/// `#[serde(deserialize_with = "latency")]`.
#[macro_export]
macro_rules! ranged_fields {
    ($($name:ident: $lo:expr, $hi:expr;)*) => {$(
        fn $name<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
            $crate::util::check::in_range(d, $lo, $hi)
        }
    )*};
}

/// Three finite numbers `[x, y, z]` (positions, velocities), as `glam::DVec3`.
pub fn vec3<'de, D: Deserializer<'de>>(d: D) -> Result<glam::DVec3, D::Error> {
    let v = <[f64; 3]>::deserialize(d)?;
    if v.iter().any(|c| !c.is_finite()) {
        return Err(D::Error::custom(format!(
            "components must be finite, got {v:?}"
        )));
    }
    Ok(glam::DVec3::from_array(v))
}

/// An optional [`non_negative`] number (for `#[serde(default)]` fields).
pub fn opt_non_negative<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
    non_negative(d).map(Some)
}

/// An optional [`positive`] number written as RON's `Some(x)`, or `None`.
pub fn opt_positive<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
    match Option::<f64>::deserialize(d)? {
        Some(v) if !v.is_finite() || v <= 0.0 => Err(D::Error::custom(format!(
            "must be a finite number > 0 (or None), got {v}"
        ))),
        v => Ok(v),
    }
}

/// Largest distance from the origin a position may have on any axis, m:
/// the sparring room is a few metres across; this leaves room for props
/// thrown far, not for typos such as 1e6.
pub const MAX_POSITION: f64 = 100.0;

/// A point in the sparring room: a [`vec3`] with every component within
/// [`MAX_POSITION`] metres of the origin.
pub fn position<'de, D: Deserializer<'de>>(d: D) -> Result<glam::DVec3, D::Error> {
    let v = vec3(d)?;
    if v.abs().max_element() > MAX_POSITION {
        return Err(D::Error::custom(format!(
            "must be within {MAX_POSITION} m of the origin on each axis, got {v}"
        )));
    }
    Ok(v)
}

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
