//! Building a linkage by clicking: each tool of the page is one step here that writes the
//! scene's TOML — the same `kind = "linkage"` file the command line reads (docs/linkage.md)
//! — and keeps everything else in it as written.
//!
//! | tool | what it writes |
//! |---|---|
//! | new | an empty linkage scene in mm or SI |
//! | pivot | a ground point `O1`, `O2`, … under `[ground] points` |
//! | link (2 clicks), ternary link (3 clicks) | a `[[body]]` through the points clicked, in its link frame (first point at the origin, second on the x axis); an end on an existing point is pinned to it by a revolute `[[joint]]` |
//! | joint | a new point of a body at the place clicked (for a later link to pin to) |
//! | slider | a one-point `[[body]]` pinned to the point clicked, sliding (prismatic `[[joint]]`) on the guide through the next two clicks |
//! | trace | a `[[measure]]` of the point's x, y, velocities and accelerations: its path is drawn, its diagrams plotted |
//! | driver | the `[[driver]]` turning the link about its ground pivot at ω (`law = "ω*t"`), and `time` over one turn in 360 steps |
//!
//! The places are where the sketch shows them: ground points where they are, body points
//! where each body's starting placement (`at`, `angle_deg`) puts them ([`sketch`]). A step
//! may leave a scene the command line refuses (a link not yet joined, no driver yet): the
//! page then shows the command line's message and the sketch, and keeps the last picture
//! that solved.

use serde::{Deserialize, Serialize};

use super::PageError;
use super::edit::{document, number};
use super::reshape::coords;
use super::session::table;
use crate::geom::{Point, Vector};

/// One end of a link, or a point a tool is aimed at, as clicked.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum End {
    /// An existing point, `ground.O1` or `crank.A`.
    Point(String),
    /// A new place, model units.
    At([f64; 2]),
}

/// A build step (the page's tools).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "tool", rename_all = "snake_case")]
pub enum Step {
    /// A new, empty linkage scene.
    New {
        /// `"mm"` or `"SI"`.
        units: String,
    },
    /// A ground pivot at a place.
    Pivot {
        /// Where, model units.
        at: [f64; 2],
    },
    /// A link (body) through two or three points.
    Link {
        /// Its points, in order.
        ends: Vec<End>,
    },
    /// A new point on a body.
    Joint {
        /// The body.
        body: String,
        /// Where, model units.
        at: [f64; 2],
    },
    /// A slider block pinned at `point`, sliding on the guide from `guide[0]` to `guide[1]`.
    Slider {
        /// The point the block is pinned to.
        point: End,
        /// The guide's two points (ground points, existing or new).
        guide: [End; 2],
    },
    /// Trace a body point: its path drawn, its x, y, velocities and accelerations measured.
    Trace {
        /// The point, `body.P`.
        point: String,
    },
    /// The driver: this body turned about its ground pivot at `omega` rad/s.
    Driver {
        /// The body.
        body: String,
        /// Angular velocity, rad/s (counter-clockwise positive).
        omega: f64,
    },
}

/// Positions in one turn of a built driver.
pub const STEPS_PER_TURN: u32 = 360;

/// The text of a new, empty linkage scene in `units`.
pub fn new_scene(units: &str) -> Result<String, PageError> {
    let (units, words) = match units {
        "mm" => ("mm", "mm, s, kg, N"),
        "SI" | "m" | "si" => ("SI", "m, s, kg, N"),
        other => return Err(PageError::Build(format!("units `{other}`: a new scene is in \"mm\" or \"SI\""))),
    };
    Ok(format!(
        "# A linkage built on the mechdraw page (docs/web.md): place ground pivots, draw links,\n\
         # choose the driver. Units {words}. Every number can be changed in the fields or here.\n\
         kind = \"linkage\"\n\
         name = \"my-linkage\"\n\
         units = \"{units}\"\n\
         time = {{ from = 0.0, to = 1.0, steps = {STEPS_PER_TURN} }}\n\
         \n\
         [ground]\n\
         points = {{}}\n"
    ))
}

/// `text` after the build `step`, coordinates written with `decimals` decimals.
pub fn apply(text: &str, file: &str, step: &Step, decimals: usize) -> Result<String, PageError> {
    if let Step::New { units } = step {
        return new_scene(units);
    }
    let t = table(text, file)?;
    if t.get("kind").and_then(toml::Value::as_str) != Some("linkage") {
        return Err(PageError::Build(
            "the build tools draw a linkage (kind = \"linkage\"); start one with New, or edit this scene's fields"
                .into(),
        ));
    }
    let sk = sketch(&t);
    let mut b = Builder { doc: document(text, file)?, sketch: sk, decimals };
    match step {
        // Answered above, before a document is opened.
        Step::New { .. } => {}
        Step::Pivot { at } => {
            b.ground_point(Point::new(at[0], at[1]), "O");
        }
        Step::Link { ends } => b.link(ends)?,
        Step::Joint { body, at } => b.joint(body, Point::new(at[0], at[1]))?,
        Step::Slider { point, guide } => b.slider(point, guide)?,
        Step::Trace { point } => b.trace(point)?,
        Step::Driver { body, omega } => b.driver(body, *omega)?,
    }
    Ok(b.doc.to_string())
}

/// A point of the sketch.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SketchPoint {
    /// `ground.O1` or `body.P`.
    pub name: String,
    /// x, model units.
    pub x: f64,
    /// y, model units.
    pub y: f64,
}

/// A link of the sketch: a body and its points.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SketchLink {
    /// The body's name.
    pub body: String,
    /// Its points' names (`body.P`), in file order.
    pub points: Vec<String>,
}

/// What the scene's text places where, without solving: ground points where they are,
/// body points where each body's starting placement puts them — what the build tools
/// click on, drawn over the picture (and alone while the scene does not solve).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Sketch {
    /// Length unit, `mm` or `m`.
    pub units: String,
    /// Every point.
    pub points: Vec<SketchPoint>,
    /// Every body.
    pub links: Vec<SketchLink>,
    /// Prismatic joints: (sliding point, guide's two points).
    pub sliders: Vec<(String, [String; 2])>,
    /// Revolute joints: the two points.
    pub pins: Vec<[String; 2]>,
    /// Bodies a driver turns.
    pub driven: Vec<String>,
    /// Traced (measured) points.
    pub traced: Vec<String>,
}

impl Sketch {
    fn at(&self, name: &str) -> Option<Point> {
        self.points.iter().find(|p| p.name == name).map(|p| Point::new(p.x, p.y))
    }

    /// Every point name in use, without its owner (`O1`, `A`).
    fn used(&self) -> Vec<&str> {
        self.points.iter().filter_map(|p| p.name.split_once('.').map(|(_, n)| n)).collect()
    }
}

/// The sketch of a scene's TOML table (any kind; only a linkage has one).
pub fn sketch(t: &toml::Table) -> Sketch {
    let mut s = Sketch {
        units: if t.get("units").and_then(toml::Value::as_str) == Some("mm") { "mm" } else { "m" }.into(),
        ..Sketch::default()
    };
    if let Some(g) = t.get("ground").and_then(|g| g.get("points")).and_then(toml::Value::as_table) {
        for (n, v) in g {
            if let Some(p) = coords(v) {
                s.points.push(SketchPoint { name: format!("ground.{n}"), x: p.x, y: p.y });
            }
        }
    }
    let list = |key: &str| t.get(key).and_then(toml::Value::as_array).cloned().unwrap_or_default();
    for b in list("body") {
        let Some(name) = b.get("name").and_then(toml::Value::as_str) else { continue };
        let at = b.get("at").and_then(coords).unwrap_or(Point::origin());
        let angle = b.get("angle_deg").and_then(|a| a.as_float().or(a.as_integer().map(|i| i as f64))).unwrap_or(0.0);
        let mut link = SketchLink { body: name.to_string(), points: Vec::new() };
        for (p, v) in b.get("points").and_then(toml::Value::as_table).into_iter().flatten() {
            if let Some(local) = coords(v) {
                let w = at + turn(local.coords, angle.to_radians());
                link.points.push(format!("{name}.{p}"));
                s.points.push(SketchPoint { name: format!("{name}.{p}"), x: w.x, y: w.y });
            }
        }
        s.links.push(link);
    }
    let str_of = |v: Option<&toml::Value>| v.and_then(toml::Value::as_str).map(str::to_string);
    for j in list("joint") {
        if let Some(r) = j.get("revolute").and_then(toml::Value::as_array)
            && let (Some(a), Some(b)) = (str_of(r.first()), str_of(r.get(1)))
        {
            s.pins.push([a, b]);
        }
        if let Some(p) = j.get("prismatic")
            && let (Some(point), Some(line)) = (str_of(p.get("point")), p.get("line").and_then(toml::Value::as_array))
            && let (Some(a), Some(b)) = (str_of(line.first()), str_of(line.get(1)))
        {
            s.sliders.push((point, [a, b]));
        }
    }
    for d in list("driver") {
        if let Some(b) = str_of(d.get("body")) {
            s.driven.push(b);
        } else if let Some(j) = str_of(d.get("joint")) {
            let joint = list("joint").into_iter().find(|x| str_of(x.get("name")).as_deref() == Some(j.as_str()));
            if let Some(second) = joint.as_ref().and_then(|x| x.get("revolute")).and_then(|r| str_of(r.get(1))) {
                s.driven.extend(second.split('.').next().map(str::to_string));
            }
        }
    }
    for m in list("measure") {
        s.traced.extend(str_of(m.get("point")));
    }
    s
}

/// `v` turned by `a` radians counter-clockwise.
fn turn(v: Vector, a: f64) -> Vector {
    let (s, c) = (libm::sin(a), libm::cos(a));
    Vector::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

/// A document being built on, with its sketch before the step.
struct Builder {
    doc: toml_edit::DocumentMut,
    sketch: Sketch,
    decimals: usize,
}

impl Builder {
    /// `[x, y]` on the grid, as the student would type it.
    fn pair(&self, p: Point) -> toml_edit::Value {
        let text = format!("[{}, {}]", number(p.x, self.decimals), number(p.y, self.decimals));
        text.parse::<toml_edit::Value>().unwrap_or_else(|_| toml_edit::Value::Array(toml_edit::Array::new()))
    }

    /// A point name not in use: `prefix1`, `prefix2`, … for ground points (`O`, `G`), the
    /// next free capital letter for a body's point.
    fn fresh_point(&self, prefix: &str, taken: &[String]) -> String {
        let used = self.sketch.used();
        let free = |n: &str| !used.contains(&n) && !taken.iter().any(|t| t == n);
        if prefix.is_empty() {
            let letters = ('A'..='Z').filter(|c| *c != 'O').map(String::from);
            if let Some(n) = letters.clone().find(|n| free(n)) {
                return n;
            }
            return (1..)
                .flat_map(|i| letters.clone().map(move |l| format!("{l}{i}")))
                .find(|n| free(n))
                .unwrap_or_default();
        }
        (1..).map(|i| format!("{prefix}{i}")).find(|n| free(n)).unwrap_or_default()
    }

    /// Adds a ground point at `p` named `prefix1`, `prefix2`, …; returns `ground.NAME`.
    fn ground_point(&mut self, p: Point, prefix: &str) -> String {
        let name = self.fresh_point(prefix, &[]);
        let value = self.pair(p);
        let ground = self.doc.entry("ground").or_insert(toml_edit::Item::Table(toml_edit::Table::new()));
        if let Some(t) = ground.as_table_like_mut() {
            let points = t.entry("points").or_insert(toml_edit::value(toml_edit::InlineTable::new()));
            if let Some(pts) = points.as_inline_table_mut() {
                pts.insert(&name, value);
                pts.fmt();
            }
        }
        self.sketch.points.push(SketchPoint { name: format!("ground.{name}"), x: p.x, y: p.y });
        format!("ground.{name}")
    }

    /// The place of an end, and the existing point it is (if any).
    fn place(&self, e: &End) -> Result<(Point, Option<String>), PageError> {
        match e {
            End::At(p) => Ok((Point::new(p[0], p[1]), None)),
            End::Point(n) => Ok((
                self.sketch.at(n).ok_or_else(|| PageError::Build(format!("no point `{n}` in the sketch")))?,
                Some(n.clone()),
            )),
        }
    }

    fn array_of_tables(&mut self, key: &str) -> Result<&mut toml_edit::ArrayOfTables, PageError> {
        let item = self.doc.entry(key).or_insert(toml_edit::Item::ArrayOfTables(toml_edit::ArrayOfTables::new()));
        item.as_array_of_tables_mut()
            .ok_or_else(|| PageError::Build(format!("`{key}` is not a list of [[{key}]] tables")))
    }

    fn body_names(&self) -> Vec<String> {
        self.sketch.links.iter().map(|l| l.body.clone()).collect()
    }

    fn fresh_body(&self, prefix: &str) -> String {
        let names = self.body_names();
        (1..).map(|i| format!("{prefix}{i}")).find(|n| !names.contains(n)).unwrap_or_default()
    }

    /// A revolute joint pinning `a` to `b`, named after the point.
    fn pin(&mut self, a: &str, b: &str) -> Result<(), PageError> {
        let point = b.split_once('.').map_or(b, |(_, p)| p).to_string();
        let names: Vec<String> = self
            .doc
            .get("joint")
            .and_then(toml_edit::Item::as_array_of_tables)
            .map(|js| js.iter().filter_map(|j| j.get("name")?.as_str().map(str::to_string)).collect())
            .unwrap_or_default();
        let name = std::iter::once(point.clone())
            .chain((2..).map(|i| format!("{point}{i}")))
            .find(|n| !names.contains(n))
            .unwrap_or_default();
        let mut j = toml_edit::Table::new();
        j.insert("name", toml_edit::value(name));
        let mut r = toml_edit::Array::new();
        r.push(a);
        r.push(b);
        j.insert("revolute", toml_edit::value(r));
        self.array_of_tables("joint")?.push(j);
        self.sketch.pins.push([a.to_string(), b.to_string()]);
        Ok(())
    }

    /// A body named `name` through the places `at` (names for its points given), in its
    /// link frame, placed where they are.
    fn body(&mut self, name: &str, points: &[(String, Point)]) -> Result<(), PageError> {
        let origin = points[0].1;
        let angle = match points.get(1) {
            Some((_, p)) if (*p - origin).norm() > 0.0 => libm::atan2(p.y - origin.y, p.x - origin.x),
            Some(_) => return Err(PageError::Build("a link's two ends are at the same place".into())),
            None => 0.0,
        };
        let mut pts = toml_edit::InlineTable::new();
        for (i, (n, p)) in points.iter().enumerate() {
            let local = match i {
                0 => Point::origin(),
                1 => Point::new((*p - origin).norm(), 0.0),
                _ => Point::origin() + turn(*p - origin, -angle),
            };
            pts.insert(n, self.pair(local));
        }
        pts.fmt();
        let mut t = toml_edit::Table::new();
        t.insert("name", toml_edit::value(name));
        t.insert("points", toml_edit::value(pts));
        t.insert("at", toml_edit::value(self.pair(origin)));
        t.insert("angle_deg", toml_edit::value(number(angle.to_degrees(), 2).parse::<f64>().unwrap_or(0.0)));
        self.array_of_tables("body")?.push(t);
        let placed: Vec<String> = points.iter().map(|(n, _)| format!("{name}.{n}")).collect();
        for (full, (_, p)) in placed.iter().zip(points) {
            self.sketch.points.push(SketchPoint { name: full.clone(), x: p.x, y: p.y });
        }
        self.sketch.links.push(SketchLink { body: name.to_string(), points: placed });
        Ok(())
    }

    fn link(&mut self, ends: &[End]) -> Result<(), PageError> {
        if !(2..=3).contains(&ends.len()) {
            return Err(PageError::Build(format!("a link joins 2 or 3 points, not {}", ends.len())));
        }
        let name = self.fresh_body("link");
        let mut points: Vec<(String, Point)> = Vec::new();
        let mut pins = Vec::new();
        for e in ends {
            let (p, existing) = self.place(e)?;
            let taken: Vec<String> = points.iter().map(|(n, _)| n.clone()).collect();
            let local = match &existing {
                Some(full) => {
                    let n = full.split_once('.').map_or(full.as_str(), |(_, n)| n).to_string();
                    if taken.contains(&n) { self.fresh_point("", &taken) } else { n }
                }
                None => self.fresh_point("", &taken),
            };
            if let Some(full) = existing {
                if full.starts_with(&format!("{name}.")) || points.iter().any(|(_, q)| (*q - p).norm() == 0.0) {
                    return Err(PageError::Build("a link's ends are at the same place".into()));
                }
                pins.push((full, format!("{name}.{local}")));
            }
            points.push((local, p));
        }
        self.body(&name, &points)?;
        for (a, b) in pins {
            self.pin(&a, &b)?;
        }
        Ok(())
    }

    fn joint(&mut self, body: &str, at: Point) -> Result<(), PageError> {
        let (o, angle) = self.placement(body);
        let local = Point::origin() + turn(at - o, -angle);
        let name = self.fresh_point("", &[]);
        let value = self.pair(local);
        let bodies = self.array_of_tables("body")?;
        let b = bodies
            .iter_mut()
            .find(|b| b.get("name").and_then(toml_edit::Item::as_str) == Some(body))
            .ok_or_else(|| PageError::Build(format!("no body `{body}`")))?;
        let points = b
            .get_mut("points")
            .and_then(toml_edit::Item::as_inline_table_mut)
            .ok_or_else(|| PageError::Build(format!("body `{body}` has no inline `points` table")))?;
        points.insert(&name, value);
        points.fmt();
        Ok(())
    }

    /// A body's starting placement as its text has it: (origin, angle in radians).
    fn placement(&self, body: &str) -> (Point, f64) {
        let b = self
            .doc
            .get("body")
            .and_then(toml_edit::Item::as_array_of_tables)
            .and_then(|bs| bs.iter().find(|b| b.get("name").and_then(toml_edit::Item::as_str) == Some(body)));
        let num = |i: &toml_edit::Item| i.as_float().or(i.as_integer().map(|v| v as f64));
        let at = b
            .and_then(|b| b.get("at"))
            .and_then(toml_edit::Item::as_array)
            .and_then(|a| {
                let v = |i: usize| a.get(i).and_then(|x| x.as_float().or(x.as_integer().map(|v| v as f64)));
                Some(Point::new(v(0)?, v(1)?))
            })
            .unwrap_or(Point::origin());
        let angle = b.and_then(|b| b.get("angle_deg")).and_then(num).unwrap_or(0.0);
        (at, angle.to_radians())
    }

    fn slider(&mut self, point: &End, guide: &[End; 2]) -> Result<(), PageError> {
        let (p, existing) = self.place(point)?;
        let mut line = Vec::new();
        for g in guide {
            let name = match g {
                End::Point(n) if n.starts_with("ground.") => {
                    self.place(g)?;
                    n.clone()
                }
                End::Point(n) => {
                    return Err(PageError::Build(format!("a guide runs through ground points; `{n}` is on a body")));
                }
                End::At(q) => self.ground_point(Point::new(q[0], q[1]), "G"),
            };
            line.push(name);
        }
        if self.sketch.at(&line[0]) == self.sketch.at(&line[1]) {
            return Err(PageError::Build("a guide's two points are at the same place".into()));
        }
        let name = self.fresh_body("slider");
        let local = match &existing {
            Some(full) => full.split_once('.').map_or(full.as_str(), |(_, n)| n).to_string(),
            None => self.fresh_point("", &[]),
        };
        self.body(&name, &[(local.clone(), p)])?;
        if let Some(full) = existing {
            self.pin(&full, &format!("{name}.{local}"))?;
        }
        let mut pr = toml_edit::InlineTable::new();
        pr.insert("point", format!("{name}.{local}").into());
        let mut l = toml_edit::Array::new();
        l.push(line[0].as_str());
        l.push(line[1].as_str());
        pr.insert("line", toml_edit::Value::Array(l));
        let mut j = toml_edit::Table::new();
        j.insert("name", toml_edit::value(format!("guide{}", name.trim_start_matches("slider"))));
        j.insert("prismatic", toml_edit::value(pr));
        self.array_of_tables("joint")?.push(j);
        Ok(())
    }

    fn trace(&mut self, point: &str) -> Result<(), PageError> {
        if point.starts_with("ground.") || self.sketch.at(point).is_none() {
            return Err(PageError::Build(format!("trace a point of a link; `{point}` is not one")));
        }
        if self.sketch.traced.iter().any(|t| t == point) {
            return Err(PageError::Build(format!("`{point}` is traced already")));
        }
        let mut m = toml_edit::Table::new();
        m.insert("point", toml_edit::value(point));
        let mut q = toml_edit::Array::new();
        for s in ["x", "y", "vx", "vy", "ax", "ay"] {
            q.push(s);
        }
        m.insert("quantities", toml_edit::value(q));
        self.array_of_tables("measure")?.push(m);
        Ok(())
    }

    fn driver(&mut self, body: &str, omega: f64) -> Result<(), PageError> {
        if !(omega.is_finite() && omega != 0.0) {
            return Err(PageError::Build(format!("ω = {omega} rad/s: a driver turns at a non-zero speed")));
        }
        // The revolute that pins the body to the ground.
        let joints = self.doc.get("joint").and_then(toml_edit::Item::as_array_of_tables);
        let pinned = joints.and_then(|js| {
            js.iter().find_map(|j| {
                let r = j.get("revolute")?.as_array()?;
                let (a, b) = (r.get(0)?.as_str()?, r.get(1)?.as_str()?);
                let ok = a.starts_with("ground.") && b.starts_with(&format!("{body}."));
                ok.then(|| j.get("name").and_then(toml_edit::Item::as_str).map(str::to_string))
            })
        });
        let joint = match pinned {
            Some(Some(name)) => name,
            _ => {
                return Err(PageError::Build(format!(
                    "the driver turns a link about its ground pivot; `{body}` has none (draw it from a pivot first)"
                )));
            }
        };
        self.doc.remove("driver");
        let mut d = toml_edit::Table::new();
        d.insert("joint", toml_edit::value(joint));
        d.insert("law", toml_edit::value(format!("{}*t", number(omega, 6).trim_end_matches(".0"))));
        self.array_of_tables("driver")?.push(d);
        // One turn in STEPS_PER_TURN steps.
        let turn = std::f64::consts::TAU / omega.abs();
        let time = format!("{{ from = 0.0, to = {turn:?}, steps = {STEPS_PER_TURN} }}");
        let mut value = time.parse::<toml_edit::Value>().map_err(|e| PageError::Build(e.to_string()))?;
        if let Some(old) = self.doc.get("time").and_then(toml_edit::Item::as_value) {
            *value.decor_mut() = old.decor().clone();
        }
        self.doc.insert("time", toml_edit::Item::Value(value));
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::web::Session;

    fn step(text: &str, s: serde_json::Value) -> Result<String, PageError> {
        apply(text, "built.toml", &serde_json::from_value(s).unwrap(), 4)
    }

    /// The Chebyshev four-bar as a student draws it: two pivots, the crank to a grid point,
    /// the coupler A–B–M through two rough clicks, the rocker from B to the second pivot,
    /// the crank driven at 20 rad/s, M traced; then the three lengths typed in the fields.
    pub(crate) fn chebyshev() -> String {
        use serde_json::json;
        let mut t = step("", json!({"tool": "new", "units": "SI"})).unwrap();
        for s in [
            json!({"tool": "pivot", "at": [0.0, 0.0]}),
            json!({"tool": "pivot", "at": [0.08, 0.0]}),
            json!({"tool": "link", "ends": ["ground.O1", [0.04, 0.0]]}),
            json!({"tool": "link", "ends": ["link1.A", [0.06, 0.1], [0.08, 0.195]]}),
            json!({"tool": "link", "ends": ["link2.B", "ground.O2"]}),
            json!({"tool": "driver", "body": "link1", "omega": 20.0}),
            json!({"tool": "trace", "point": "link2.C"}),
        ] {
            t = step(&t, s.clone()).unwrap_or_else(|e| panic!("{s}: {e}"));
        }
        let fields =
            [("body[1].points.B[0]", "0.1"), ("body[1].points.C", "[0.2, 0.0]"), ("body[2].points.O2[0]", "0.1")];
        crate::web::edit::set(&t, "built.toml", &fields.map(|(p, v)| (p.to_string(), v.to_string()))).unwrap()
    }

    #[test]
    fn the_chebyshev_four_bar_built_by_clicks_moves_as_the_template() {
        let built = chebyshev();
        assert!(built.starts_with("# A linkage built on the mechdraw page"), "{built}");
        let s = Session::new(&built, "built.toml").unwrap_or_else(|e| panic!("{e}\n{built}"));
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates/fourbar-chebyshev.toml");
        let template = Session::new(&std::fs::read_to_string(path).unwrap(), "fourbar-chebyshev.toml").unwrap();
        assert_eq!(s.positions(), 361);
        for k in [0, 45, 90, 200, 300] {
            let (a, b) = (s.points(k).unwrap(), template.points(k).unwrap());
            let at = |st: &crate::figure::shared::animation::DriveState, n: &str| {
                st.points.iter().find(|(m, _)| m == n).unwrap_or_else(|| panic!("{n}")).1
            };
            for (mine, theirs) in [("link1.A", "A"), ("link2.B", "B"), ("link2.C", "M"), ("link3.O2", "C")] {
                let d = (at(&a, mine) - at(&b, theirs)).norm();
                assert!(d < 1e-12, "position {k}: {mine} is {d} m from the template's {theirs}");
            }
        }
    }

    #[test]
    fn steps_that_cannot_be_made_say_why() {
        use serde_json::json;
        let t = step("", json!({"tool": "new", "units": "mm"})).unwrap();
        let t = step(&t, json!({"tool": "link", "ends": [[0.0, 0.0], [40.0, 0.0]]})).unwrap();
        let e = step(&t, json!({"tool": "driver", "body": "link1", "omega": 1.0})).unwrap_err().to_string();
        assert!(e.contains("`link1` has none"), "{e}");
        let e = step(&t, json!({"tool": "link", "ends": ["link1.A", "link1.A"]})).unwrap_err().to_string();
        assert!(e.contains("same place"), "{e}");
        let e = step(&t, json!({"tool": "trace", "point": "ground.X"})).unwrap_err().to_string();
        assert!(e.contains("not one"), "{e}");
        let fourbar = include_str!("../../templates/fourbar-chebyshev.toml");
        let e = step(fourbar, json!({"tool": "pivot", "at": [0.0, 0.0]})).unwrap_err().to_string();
        assert!(e.contains("kind = \"linkage\""), "{e}");
        // A half-built linkage is a scene the command line refuses, in its words.
        let e = Session::new(&t, "built.toml").unwrap_err().to_string();
        assert!(e.starts_with("built.toml: "), "{e}");
    }

    #[test]
    fn a_slider_crank_built_by_clicks_solves() {
        use serde_json::json;
        let mut t = step("", json!({"tool": "new", "units": "mm"})).unwrap();
        for s in [
            json!({"tool": "pivot", "at": [0.0, 0.0]}),
            json!({"tool": "link", "ends": ["ground.O1", [30.0, 0.0]]}),
            json!({"tool": "link", "ends": ["link1.A", [130.0, 0.0]]}),
            json!({"tool": "slider", "point": "link2.B", "guide": [[0.0, 0.0], [200.0, 0.0]]}),
            json!({"tool": "driver", "body": "link1", "omega": 10.0}),
        ] {
            t = step(&t, s.clone()).unwrap_or_else(|e| panic!("{s}: {e}"));
        }
        let s = Session::new(&t, "built.toml").unwrap_or_else(|e| panic!("{e}\n{t}"));
        // The piston's stroke: 2 × the crank, with the piston on the guide at every position.
        let xs: Vec<f64> = (0..s.positions())
            .map(|k| s.points(k).unwrap().points.iter().find(|(n, _)| n == "slider1.B").unwrap().1.x)
            .collect();
        let (lo, hi) = xs.iter().fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(*x), b.max(*x)));
        assert!((hi - lo - 60.0).abs() < 1e-9, "stroke {}", hi - lo);
        // The text keeps what was there: every step added, none rewritten.
        assert!(t.contains("[ground]\npoints = { O1 = [0.0, 0.0], G1 = [0.0, 0.0], G2 = [200.0, 0.0] }"), "{t}");
    }
}
