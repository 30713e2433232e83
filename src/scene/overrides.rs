//! `--set KEY=VALUE` overrides: change any scene field from the command line, checked
//! like the file itself.
//!
//! KEY is a dotted path with optional array indices: `l12`, `pattern.tol`, `r[2]`,
//! `dynamics.m1`, `dynamics.force[0].value`. VALUE is a TOML value (`55`, `1e-6`,
//! `[15, 30]`, `"left"`, `true`); a bare word that is not TOML is taken as a string, so
//! `--set name=demo` works.

use super::SceneError;

/// One step of a key path.
#[derive(Debug, Clone, PartialEq)]
enum Step {
    Key(String),
    Index(usize),
}

/// A parsed `--set KEY=VALUE`.
#[derive(Debug, Clone, PartialEq)]
pub struct Override {
    spec: String,
    path: Vec<Step>,
    value: toml::Value,
    /// The value as written (a bare word that is not TOML is a string).
    value_text: String,
}

impl std::str::FromStr for Override {
    type Err = SceneError;

    fn from_str(spec: &str) -> Result<Override, SceneError> {
        let err = |message: &str| SceneError::Override { spec: spec.to_string(), message: message.to_string() };
        let (key, value) =
            spec.split_once('=').ok_or_else(|| err("expected KEY=VALUE, e.g. l12=55 or pattern.tol=1e-6"))?;
        let path = parse_path(key.trim()).map_err(|m| err(&m))?;
        let value_text = value.trim();
        if value_text.is_empty() {
            return Err(err("the value is empty"));
        }
        let value = match format!("v = {value_text}").parse::<toml::Table>() {
            Ok(mut t) => t.remove("v").unwrap_or(toml::Value::String(value_text.to_string())),
            Err(_) if value_text.chars().all(|c| c.is_alphanumeric() || "-_.".contains(c)) => {
                toml::Value::String(value_text.to_string())
            }
            Err(e) => return Err(err(&format!("the value is not a TOML value: {}", e.message()))),
        };
        Ok(Override { spec: spec.to_string(), path, value, value_text: value_text.to_string() })
    }
}

fn parse_path(key: &str) -> Result<Vec<Step>, String> {
    let mut steps = Vec::new();
    for part in key.split('.') {
        let (name, mut rest) = match part.find('[') {
            Some(i) => (&part[..i], &part[i..]),
            None => (part, ""),
        };
        if name.is_empty() || !name.chars().all(|c| c.is_alphanumeric() || c == '_' || c == '-') {
            return Err(format!(
                "`{}` is not a field path (use names like l12, pattern.tol, r[2])",
                crate::text::excerpt(key)
            ));
        }
        steps.push(Step::Key(name.to_string()));
        while !rest.is_empty() {
            let close = rest.find(']').ok_or_else(|| format!("unclosed `[` in `{key}`"))?;
            let idx: usize = rest[1..close]
                .trim()
                .parse()
                .map_err(|_| format!("`{}` is not an array index in `{key}`", &rest[1..close]))?;
            steps.push(Step::Index(idx));
            rest = &rest[close + 1..];
            if !rest.is_empty() && !rest.starts_with('[') {
                return Err(format!("unexpected `{rest}` in `{key}`"));
            }
        }
    }
    Ok(steps)
}

impl Override {
    /// Sets the value in `table`, creating missing tables on the way (an unknown field is
    /// then refused by the schema, like one in the file).
    pub fn apply(&self, table: &mut toml::Table) -> Result<(), SceneError> {
        let err = |message: String| SceneError::Override { spec: self.spec.clone(), message };
        let mut slot: Option<&mut toml::Value> = None;
        let mut cur_table: Option<&mut toml::Table> = Some(table);
        for (i, step) in self.path.iter().enumerate() {
            let last = i + 1 == self.path.len();
            let next: &mut toml::Value = match (step, cur_table.take(), slot.take()) {
                (Step::Key(k), Some(t), _) => {
                    if last {
                        t.insert(k.clone(), self.value.clone());
                        return Ok(());
                    }
                    let next_is_index = matches!(self.path[i + 1], Step::Index(_));
                    t.entry(k.clone()).or_insert_with(|| {
                        if next_is_index {
                            toml::Value::Array(Vec::new())
                        } else {
                            toml::Value::Table(toml::Table::new())
                        }
                    })
                }
                (Step::Key(k), None, Some(toml::Value::Table(t))) => {
                    if last {
                        t.insert(k.clone(), self.value.clone());
                        return Ok(());
                    }
                    t.entry(k.clone()).or_insert_with(|| toml::Value::Table(toml::Table::new()))
                }
                (Step::Index(n), None, Some(toml::Value::Array(a))) => {
                    let len = a.len();
                    let item = a
                        .get_mut(*n)
                        .ok_or_else(|| err(format!("index {n} is past the end (the array has {len} items)")))?;
                    if last {
                        *item = self.value.clone();
                        return Ok(());
                    }
                    item
                }
                (Step::Index(_), ..) => return Err(err("indexes something that is not an array".into())),
                (Step::Key(k), ..) => return Err(err(format!("`{k}` is inside something that is not a table"))),
            };
            if let toml::Value::Table(t) = next {
                cur_table = Some(t);
            } else {
                slot = Some(next);
            }
        }
        Ok(())
    }
}

impl Override {
    /// The field path as written (`l12`, `r[2]`, `dynamics.force[0].value`).
    pub fn key(&self) -> &str {
        self.spec.split_once('=').map_or("", |(k, _)| k.trim())
    }

    /// Writes the value into the scene's text `doc` as the student would: the value at the
    /// path is replaced and nothing else changes (its comments, the order and layout of the
    /// file, the number's own spelling when the value is the same number). What
    /// [`Override::apply`] creates (a missing table or key) is added. Refuses what `apply`
    /// refuses, with the same messages.
    pub fn apply_to_document(&self, doc: &mut toml_edit::DocumentMut) -> Result<(), SceneError> {
        let err = |message: String| SceneError::Override { spec: self.spec.clone(), message };
        let new = self.document_value();
        let mut item: &mut toml_edit::Item = doc.as_item_mut();
        for (i, step) in self.path.iter().enumerate() {
            let last = i + 1 == self.path.len();
            match step {
                Step::Key(k) => {
                    if item.get(k.as_str()).is_none_or(toml_edit::Item::is_none) {
                        let fresh = if last {
                            toml_edit::Item::Value(new.clone())
                        } else if matches!(self.path[i + 1], Step::Index(_)) {
                            toml_edit::value(toml_edit::Array::new())
                        } else if item.is_table() {
                            toml_edit::Item::Table(toml_edit::Table::new())
                        } else {
                            toml_edit::value(toml_edit::InlineTable::new())
                        };
                        match item {
                            toml_edit::Item::Table(t) => {
                                t.insert(k, fresh);
                            }
                            toml_edit::Item::Value(toml_edit::Value::InlineTable(t)) => {
                                if let toml_edit::Item::Value(v) = fresh {
                                    t.insert(k.as_str(), v);
                                }
                            }
                            _ => return Err(err(format!("`{k}` is inside something that is not a table"))),
                        }
                        if last {
                            return Ok(());
                        }
                    }
                    item = item
                        .get_mut(k.as_str())
                        .ok_or_else(|| err(format!("`{k}` is inside something that is not a table")))?;
                }
                Step::Index(n) => {
                    let len = match &*item {
                        toml_edit::Item::ArrayOfTables(a) => a.len(),
                        toml_edit::Item::Value(toml_edit::Value::Array(a)) => a.len(),
                        _ => return Err(err("indexes something that is not an array".into())),
                    };
                    item = item
                        .get_mut(*n)
                        .ok_or_else(|| err(format!("index {n} is past the end (the array has {len} items)")))?;
                }
            }
        }
        replace_keeping_format(item, new);
        Ok(())
    }

    /// The value as the document writes it: as typed, or a string for a bare word.
    fn document_value(&self) -> toml_edit::Value {
        let mut v = self
            .value_text
            .parse::<toml_edit::Value>()
            .unwrap_or_else(|_| toml_edit::Value::from(self.value_text.as_str()));
        v.decor_mut().clear();
        v
    }
}

/// Puts `new` where `item` is, with the old value's surroundings (the spaces and the comment
/// after it); the same number (or string, or boolean) keeps its spelling.
fn replace_keeping_format(item: &mut toml_edit::Item, new: toml_edit::Value) {
    use toml_edit::Value as V;
    match item {
        toml_edit::Item::Value(old) => {
            let same = match (&*old, &new) {
                (V::Float(a), V::Float(b)) => a.value() == b.value(),
                (V::Integer(a), V::Integer(b)) => a.value() == b.value(),
                (V::String(a), V::String(b)) => a.value() == b.value(),
                (V::Boolean(a), V::Boolean(b)) => a.value() == b.value(),
                _ => false,
            };
            if !same {
                let decor = old.decor().clone();
                *old = new;
                *old.decor_mut() = decor;
            }
        }
        other => *other = toml_edit::Item::Value(new),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn apply(text: &str, spec: &str) -> Result<toml::Table, SceneError> {
        let mut t: toml::Table = text.parse().unwrap();
        spec.parse::<Override>()?.apply(&mut t)?;
        Ok(t)
    }

    #[test]
    fn sets_top_level_nested_and_indexed_fields() {
        let t = apply("l12 = 50.0\nr = [1.0, 2.0, 3.0]\n[pattern]\ntol = 1e-5\n", "l12=55").unwrap();
        assert_eq!(t["l12"].as_integer(), Some(55));
        let t = apply("[pattern]\ntol = 1e-5\n", "pattern.tol=1e-7").unwrap();
        assert_eq!(t["pattern"]["tol"].as_float(), Some(1e-7));
        let t = apply("r = [1.0, 2.0, 3.0]\n", "r[2]=84.5").unwrap();
        assert_eq!(t["r"][2].as_float(), Some(84.5));
        let t = apply("name = \"a\"\n", "name=demo-2").unwrap();
        assert_eq!(t["name"].as_str(), Some("demo-2"));
        let t = apply("o1 = [0.0, 0.0]\n", "o1=[15, 30]").unwrap();
        assert_eq!(t["o1"][1].as_integer(), Some(30));
    }

    #[test]
    fn malformed_overrides_are_named() {
        assert!(matches!("l12".parse::<Override>(), Err(SceneError::Override { .. })));
        assert!(matches!("=5".parse::<Override>(), Err(SceneError::Override { .. })));
        assert!(matches!("r[x]=5".parse::<Override>(), Err(SceneError::Override { .. })));
        assert!(matches!(apply("r = [1.0]\n", "r[3]=5"), Err(SceneError::Override { .. })));
        assert!(matches!(apply("l12 = 1.0\n", "l12.x=5"), Err(SceneError::Override { .. })));
    }

    fn edit(text: &str, spec: &str) -> Result<String, SceneError> {
        let mut d: toml_edit::DocumentMut = text.parse().unwrap();
        spec.parse::<Override>()?.apply_to_document(&mut d)?;
        Ok(d.to_string())
    }

    #[test]
    fn a_document_edit_changes_one_value_and_keeps_the_rest() {
        let text = "# head\nl12 = 50.0   # A1A2, mm\nr = [1.0, 2.0, 3.0] # radii\np = { a = [0.0, 1.0] }\n[pattern]\ntol = 1e-5\n";
        assert_eq!(edit(text, "l12=55.5").unwrap(), text.replace("50.0   #", "55.5   #"));
        assert_eq!(edit(text, "r[1]=2.5").unwrap(), text.replace("2.0, 3.0", "2.5, 3.0"));
        assert_eq!(edit(text, "p.a[1]=-2").unwrap(), text.replace("1.0] }", "-2] }"));
        assert_eq!(edit(text, "pattern.tol=1e-7").unwrap(), text.replace("1e-5", "1e-7"));
        // The same number keeps its spelling.
        assert_eq!(edit(text, "l12=50").unwrap(), text.replace("50.0", "50"), "an integer is another value");
        assert_eq!(edit(text, "l12=5e1").unwrap(), text, "5e1 is 50.0");
        // What is missing is added; the rest stays.
        let added = edit(text, "mode=3").unwrap();
        assert!(added.starts_with(text.split("[pattern]").next().unwrap()) && added.contains("mode = 3"), "{added}");
        let t: toml::Table = added.parse().unwrap();
        assert_eq!(t["mode"].as_integer(), Some(3));
        let t: toml::Table = edit(text, "newton.tol=1e-9").unwrap().parse().unwrap();
        assert_eq!(t["newton"]["tol"].as_float(), Some(1e-9));
        // The same refusals as `apply`.
        assert!(matches!(edit(text, "r[3]=5"), Err(SceneError::Override { .. })));
        assert!(matches!(edit(text, "l12.x=5"), Err(SceneError::Override { .. })));
        assert!(matches!(edit(text, "l12[0]=5"), Err(SceneError::Override { .. })));
    }

    #[test]
    fn document_and_table_edits_agree() {
        let text =
            "l12 = 50.0\nr = [1.0, 2.0, 3.0]\n[pattern]\ntol = 1e-5\n[[force]]\nat = \"M\"\nvalue = [0.0, -50.0]\n";
        for spec in [
            "l12=55",
            "r[2]=84.5",
            "pattern.tol=1e-7",
            "force[0].value[1]=-20",
            "name=demo-2",
            "o1=[15, 30]",
            "a.b.c=1",
        ] {
            let table: toml::Table = edit(text, spec).unwrap().parse().unwrap();
            assert_eq!(table, apply(text, spec).unwrap(), "{spec}");
        }
    }
}
