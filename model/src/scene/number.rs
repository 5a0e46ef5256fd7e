//! Numbers in a scene file are written as numbers. YAML's typed readers take a quoted
//! scalar as readily as a plain one (`mu_g: "1.5"` read as 1.5), so a value a tool wrote
//! as text, or a template left quoted, would pass unseen. Every number and flag of
//! [`crate::scene::file`] is read through [`number`], which asks the parser what the
//! scalar is (`deserialize_any`): a plain number is a number, quoted text is refused with
//! the field named, as any other type mismatch is.

use serde::de::{DeserializeOwned, Deserializer, Error, Unexpected, Visitor};
use serde::Deserialize;
use std::fmt;
use std::marker::PhantomData;

/// Reads a number, flag or list of them from its plain YAML form only (`serde`'s
/// `deserialize_with`).
pub fn number<'de, D: Deserializer<'de>, T: Written>(deserializer: D) -> Result<T, D::Error> {
    T::As::deserialize(deserializer).map(T::from_written)
}

/// A field type read through [`number`], and the form its value is written in.
pub trait Written: Sized {
    /// What the file holds.
    type As: DeserializeOwned;
    /// The field's value.
    fn from_written(written: Self::As) -> Self;
}

/// A real number written as a number.
pub struct Real(f64);

/// A count written as a whole number.
pub struct Count<T>(T);

/// A flag written as `true` or `false`.
pub struct Flag(bool);

const QUOTED: &str = "(numbers and flags are written without quotes)";

impl<'de> Deserialize<'de> for Real {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = Real;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                write!(f, "a number {QUOTED}")
            }
            fn visit_f64<E: Error>(self, v: f64) -> Result<Real, E> {
                Ok(Real(v))
            }
            fn visit_i64<E: Error>(self, v: i64) -> Result<Real, E> {
                Ok(Real(v as f64))
            }
            fn visit_u64<E: Error>(self, v: u64) -> Result<Real, E> {
                Ok(Real(v as f64))
            }
        }
        deserializer.deserialize_any(V)
    }
}

impl<'de, T: TryFrom<u64>> Deserialize<'de> for Count<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct V<T>(PhantomData<T>);
        impl<T: TryFrom<u64>> Visitor<'_> for V<T> {
            type Value = Count<T>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                write!(f, "a whole number, 0 or more, that fits {QUOTED}")
            }
            fn visit_u64<E: Error>(self, v: u64) -> Result<Count<T>, E> {
                T::try_from(v)
                    .map(Count)
                    .map_err(|_| E::invalid_value(Unexpected::Unsigned(v), &self))
            }
            fn visit_i64<E: Error>(self, v: i64) -> Result<Count<T>, E> {
                match u64::try_from(v) {
                    Ok(v) => self.visit_u64(v),
                    Err(_) => Err(E::invalid_value(Unexpected::Signed(v), &self)),
                }
            }
        }
        deserializer.deserialize_any(V(PhantomData))
    }
}

impl<'de> Deserialize<'de> for Flag {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = Flag;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                write!(f, "true or false {QUOTED}")
            }
            fn visit_bool<E: Error>(self, v: bool) -> Result<Flag, E> {
                Ok(Flag(v))
            }
        }
        deserializer.deserialize_any(V)
    }
}

impl Written for f64 {
    type As = Real;
    fn from_written(written: Real) -> f64 {
        written.0
    }
}

impl Written for u32 {
    type As = Count<u32>;
    fn from_written(written: Count<u32>) -> u32 {
        written.0
    }
}

impl Written for u64 {
    type As = Count<u64>;
    fn from_written(written: Count<u64>) -> u64 {
        written.0
    }
}

impl Written for bool {
    type As = Flag;
    fn from_written(written: Flag) -> bool {
        written.0
    }
}

impl<T: Written, const N: usize> Written for [T; N]
where
    [T::As; N]: DeserializeOwned,
{
    type As = [T::As; N];
    fn from_written(written: [T::As; N]) -> [T; N] {
        written.map(T::from_written)
    }
}

impl<T: Written> Written for Vec<T> {
    type As = Vec<T::As>;
    fn from_written(written: Vec<T::As>) -> Vec<T> {
        written.into_iter().map(T::from_written).collect()
    }
}

impl<T: Written> Written for Option<T> {
    type As = Option<T::As>;
    fn from_written(written: Option<T::As>) -> Option<T> {
        written.map(T::from_written)
    }
}
