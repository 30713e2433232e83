//! The guard where products become bytes: no number that is not finite reaches a writer.
//! Inputs are refused at their field when their results would overflow (the ranges of
//! [`crate::scene`]), and a quantity undefined at a position is computed by a route that
//! holds there or left out with its reason; this is the net behind both. A drawing
//! coordinate or text, a CSV field or a JSON number that is NaN or infinite fails the run
//! with [`Error::NonFinite`], naming the file and the place, before anything is written.
//! JSON has no NaN: serde_json would write `null` silently, so the summary is checked in
//! its typed form ([`check_summary`]).

use serde::Serialize;
use serde::ser;

use crate::Error;
use crate::draw::Drawing;
use crate::report::Csv;

/// Refuses a drawing with a number that is not finite; `what` names the file.
pub fn check_drawing(d: &Drawing, what: &str) -> Result<(), Error> {
    match d.first_non_finite() {
        Some(at) => Err(Error::NonFinite { what: what.to_string(), at }),
        None => Ok(()),
    }
}

/// Refuses a table with a field that writes a number that is not finite.
pub fn check_csv(csv: &Csv, what: &str) -> Result<(), Error> {
    match csv.first_non_finite() {
        Some(at) => Err(Error::NonFinite { what: what.to_string(), at }),
        None => Ok(()),
    }
}

/// Refuses a summary with a number that is not finite, naming its key path (`positions[3].Me1`).
pub fn check_summary(summary: &impl Serialize, what: &str) -> Result<(), Error> {
    let mut walker = Walker { path: Vec::new() };
    match summary.serialize(&mut walker) {
        Err(Found(Some(at))) => Err(Error::NonFinite { what: what.to_string(), at }),
        // Another serialisation error is serde_json's to report (summary_value).
        _ => Ok(()),
    }
}

/// Where a walk stopped: the key path of a number that is not finite (`None`: another error).
#[derive(Debug)]
struct Found(Option<String>);

impl std::fmt::Display for Found {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.0.as_deref().unwrap_or("(not serialisable)"))
    }
}

impl std::error::Error for Found {}

impl ser::Error for Found {
    fn custom<T: std::fmt::Display>(_: T) -> Found {
        Found(None)
    }
}

/// A serializer that writes nothing: it walks a value and stops at the first float that is
/// not finite, with the path of keys and indices that lead to it.
struct Walker {
    path: Vec<String>,
}

impl Walker {
    fn found(&self) -> Found {
        let mut at = String::new();
        for p in &self.path {
            if !p.starts_with('[') && !at.is_empty() {
                at.push('.');
            }
            at.push_str(p);
        }
        Found(Some(if at.is_empty() { "(top level)".into() } else { at }))
    }

    fn nested<T: Serialize + ?Sized>(&mut self, key: String, value: &T) -> Result<(), Found> {
        self.path.push(key);
        value.serialize(&mut *self)?;
        self.path.pop();
        Ok(())
    }
}

/// A sequence, tuple or map being walked: the next index.
struct Compound<'a> {
    walker: &'a mut Walker,
    index: usize,
    key: Option<String>,
}

impl Compound<'_> {
    fn element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Found> {
        let key = format!("[{}]", self.index);
        self.index += 1;
        self.walker.nested(key, value)
    }
}

macro_rules! plain {
    ($($name:ident: $t:ty),*) => {$(
        fn $name(self, _: $t) -> Result<(), Found> { Ok(()) }
    )*};
}

impl<'a> ser::Serializer for &'a mut Walker {
    type Ok = ();
    type Error = Found;
    type SerializeSeq = Compound<'a>;
    type SerializeTuple = Compound<'a>;
    type SerializeTupleStruct = Compound<'a>;
    type SerializeTupleVariant = Compound<'a>;
    type SerializeMap = Compound<'a>;
    type SerializeStruct = Compound<'a>;
    type SerializeStructVariant = Compound<'a>;

    plain!(serialize_bool: bool, serialize_i8: i8, serialize_i16: i16, serialize_i32: i32, serialize_i64: i64,
        serialize_u8: u8, serialize_u16: u16, serialize_u32: u32, serialize_u64: u64, serialize_char: char,
        serialize_str: &str, serialize_bytes: &[u8], serialize_unit_struct: &'static str);

    fn serialize_f32(self, v: f32) -> Result<(), Found> {
        self.serialize_f64(f64::from(v))
    }
    fn serialize_f64(self, v: f64) -> Result<(), Found> {
        if v.is_finite() { Ok(()) } else { Err(self.found()) }
    }
    fn serialize_none(self) -> Result<(), Found> {
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), Found> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), Found> {
        Ok(())
    }
    fn serialize_unit_variant(self, _: &'static str, _: u32, _: &'static str) -> Result<(), Found> {
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, _: &'static str, value: &T) -> Result<(), Found> {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<(), Found> {
        self.nested(variant.to_string(), value)
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Compound<'a>, Found> {
        Ok(Compound { walker: self, index: 0, key: None })
    }
    fn serialize_tuple(self, _: usize) -> Result<Compound<'a>, Found> {
        self.serialize_seq(None)
    }
    fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Compound<'a>, Found> {
        self.serialize_seq(None)
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, Found> {
        self.serialize_seq(None)
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Compound<'a>, Found> {
        self.serialize_seq(None)
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Compound<'a>, Found> {
        self.serialize_seq(None)
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, Found> {
        self.serialize_seq(None)
    }
}

/// The element-wise compounds: each element walked under its index.
macro_rules! by_index {
    ($($trait:ident :: $method:ident),*) => {$(
        impl ser::$trait for Compound<'_> {
            type Ok = ();
            type Error = Found;
            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Found> {
                self.element(value)
            }
            fn end(self) -> Result<(), Found> {
                Ok(())
            }
        }
    )*};
}

by_index!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field,
    SerializeTupleVariant::serialize_field
);

impl ser::SerializeMap for Compound<'_> {
    type Ok = ();
    type Error = Found;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), Found> {
        // Keys are names (strings or numbers): their JSON text names the place.
        self.key = serde_json::to_value(key).ok().map(|k| k.as_str().map_or_else(|| k.to_string(), str::to_string));
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Found> {
        match self.key.take() {
            Some(key) => self.walker.nested(key, value),
            None => self.element(value),
        }
    }
    fn end(self) -> Result<(), Found> {
        Ok(())
    }
}

/// The compounds with named fields: each field walked under its name.
macro_rules! by_name {
    ($($trait:ident),*) => {$(
        impl ser::$trait for Compound<'_> {
            type Ok = ();
            type Error = Found;
            fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Result<(), Found> {
                self.walker.nested(key.to_string(), value)
            }
            fn end(self) -> Result<(), Found> {
                Ok(())
            }
        }
    )*};
}

by_name!(SerializeStruct, SerializeStructVariant);

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    #[derive(Serialize)]
    struct Position {
        phi1_deg: f64,
        forces: BTreeMap<String, [f64; 2]>,
        me1: Option<f64>,
    }

    #[test]
    fn a_summary_names_the_path_of_its_first_number_that_is_not_finite() {
        let mut forces = BTreeMap::new();
        forces.insert("R_A".to_string(), [1.0, 2.0]);
        let ok = vec![Position { phi1_deg: 0.0, forces: forces.clone(), me1: None }];
        assert!(check_summary(&ok, "x.json").is_ok());
        forces.insert("R_B".to_string(), [1.0, f64::INFINITY]);
        let bad = vec![ok.into_iter().next().unwrap(), Position { phi1_deg: 1.0, forces, me1: Some(f64::NAN) }];
        let e = check_summary(&bad, "x.json").unwrap_err().to_string();
        assert!(e.contains("x.json") && e.contains("[1].forces.R_B[1]"), "{e}");
        let e = check_summary(&serde_json::json!({"a": [1.0]}), "x.json");
        assert!(e.is_ok());
    }

    #[test]
    fn a_drawing_or_table_with_nan_or_inf_is_refused_by_place() {
        use crate::draw::{Aci, DimStyle, LineType, Shape};
        use crate::geom::Point;
        let style = DimStyle { text_height: 1.0, arrow_size: 1.0 };
        let mut d = Drawing::new(style);
        let l = d.layer("FORCES", Aci::RED, LineType::Continuous);
        d.add(l, Shape::Line { from: Point::new(0.0, 0.0), to: Point::new(1.0, 2.0) });
        assert!(check_drawing(&d, "a.svg").is_ok());
        d.text(l, Point::new(0.0, 0.0), 1.0, "|R_A| = inf N");
        let e = check_drawing(&d, "a.svg").unwrap_err().to_string();
        assert!(e.contains("a.svg") && e.contains("FORCES") && e.contains("inf"), "{e}");
        let mut d = Drawing::new(style);
        d.add(0, Shape::Line { from: Point::new(f64::NAN, 0.0), to: Point::new(1.0, 2.0) });
        assert!(check_drawing(&d, "b.dxf").unwrap_err().to_string().contains("NaN"));
        let mut csv = Csv::new(["phi1_deg", "Me1"]);
        csv.row([1.0, 2.0]);
        assert!(check_csv(&csv, "c.csv").is_ok());
        csv.row([2.0, f64::NEG_INFINITY]);
        let e = check_csv(&csv, "c.csv").unwrap_err().to_string();
        assert!(e.contains("row 2 column Me1") && e.contains("-inf"), "{e}");
    }
}
