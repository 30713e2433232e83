//! Every number of a scene as the page's fields show it: its `--set` path (what changes it),
//! a name from the scene's meaning with its unit (`crank O1A`, `mm`; `ω1`, `rad/s`), the
//! group it belongs to (a body, the ground, the motion, the loads) and a slider range that
//! makes sense for what it is (a length stays positive, an angle turns ±180°).
//!
//! The names follow each kind's schema (docs/fourbar-solver.md, docs/linkage.md,
//! docs/triad.md, docs/chain.md, docs/synthesis.md); a number the rules do not know keeps its
//! path as its name.

/// A number of the scene that the page offers as a field and a slider.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// The `--set` path (`l_bc`, `phi1_deg.step`, `dynamics.force[0].value[1]`,
    /// `body[1].points.B[0]`).
    pub path: String,
    /// Its value in the scene's text.
    pub value: f64,
    /// Whether the scene writes it as an integer (a count: set it as one).
    pub integer: bool,
    /// What it is, as a person reads it (`crank O1A`, `ω1`, `coupler: M x`).
    pub label: String,
    /// Its unit (`mm`, `m`, `°`, `rad/s`, `kg`, `N`; empty for a count or a ratio).
    pub unit: String,
    /// The group it is shown in (`crank`, `ground`, `motion`, `loads`).
    pub group: String,
    /// The slider's range, low end.
    pub min: f64,
    /// The slider's range, high end.
    pub max: f64,
    /// A detail most students leave alone (a body's starting placement, the origin of its
    /// frame): the page shows it folded away under its group.
    pub detail: bool,
}

impl Parameter {
    /// The value as `--set` takes it (`12` for an integer, `0.125` for a float).
    pub fn text(&self) -> String {
        if self.integer { format!("{}", self.value as i64) } else { format!("{:?}", self.value) }
    }
}

/// What kind of quantity a number is: its unit and its slider's range follow.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Role {
    /// A length that must stay positive (a link, a radius).
    Length,
    /// A coordinate or an offset (any sign), in length units.
    Coordinate,
    /// An angle, degrees.
    Angle,
    /// An angular velocity, rad/s.
    AngularVelocity,
    /// An angular acceleration, rad/s².
    AngularAcceleration,
    /// A time, s.
    Time,
    /// A mass, kg.
    Mass,
    /// A moment of inertia, kg·m².
    Inertia,
    /// A force component, N.
    Force,
    /// A torque, N·m.
    Torque,
    /// A gravitational acceleration, m/s².
    Gravity,
    /// A count (steps, samples, a mode): an integer ≥ 1.
    Count,
    /// Anything else (a tolerance, a factor).
    Plain,
}

/// A number's name, group and role, found from its path.
struct Meaning {
    label: String,
    group: String,
    role: Role,
    detail: bool,
}

fn meaning(label: impl Into<String>, group: impl Into<String>, role: Role) -> Option<Meaning> {
    Some(Meaning { label: label.into(), group: group.into(), role, detail: false })
}

/// [`meaning`] of a detail ([`Parameter::detail`]).
fn detail(label: impl Into<String>, group: impl Into<String>, role: Role) -> Option<Meaning> {
    Some(Meaning { label: label.into(), group: group.into(), role, detail: true })
}

/// Every number in the scene `table` (as its text parses), depth first in the file's order,
/// named from the scene's meaning.
pub fn parameters(table: &toml::Table) -> Vec<Parameter> {
    let mut raw = Vec::new();
    numbers("", &toml::Value::Table(table.clone()), &mut raw);
    let kind = table.get("kind").and_then(toml::Value::as_str).unwrap_or("");
    let length = match table.get("units").and_then(toml::Value::as_str) {
        Some("mm") => "mm",
        _ => "m",
    };
    raw.into_iter()
        .map(|(path, value, integer)| {
            let m = match kind {
                _ if path.starts_with("tolerances.") => tolerances(&path),
                "fourbar" => fourbar(&path, table),
                "linkage" => linkage(&path, table),
                "triad" => triad(&path),
                "chain" => chain(&path),
                "synthesis" => synthesis(&path),
                _ => None,
            }
            .unwrap_or_else(|| Meaning {
                label: path.clone(),
                group: "other".into(),
                role: if integer { Role::Count } else { Role::Plain },
                detail: false,
            });
            let (min, max) = range(m.role, value, integer);
            Parameter {
                unit: unit(m.role, length).to_string(),
                label: m.label,
                group: m.group,
                path,
                value,
                integer,
                min,
                max,
                detail: m.detail,
            }
        })
        .collect()
}

/// A number of `[tolerances]` (docs/tolerances.md): a setting, or a toleranced field's band
/// (`± l_ab`, `l_ab +`, `ground.points.O[1] Cp`), in the field's unit (degrees for a
/// `…_deg` field, whose band is then a plain number).
fn tolerances(path: &str) -> Option<Meaning> {
    let rest = path.strip_prefix("tolerances.")?;
    if let Some(setting) = rest.strip_prefix("settings.") {
        let (label, role) = match setting {
            "samples" => ("Monte Carlo samples", Role::Count),
            "seed" => ("random seed", Role::Count),
            "bins" => ("histogram bins", Role::Count),
            "cp" => ("Cp of every dimension", Role::Plain),
            "k" => ("k (half band in σ)", Role::Plain),
            "trust" => ("trust fraction (MC σ vs linear)", Role::Plain),
            "magnification" => ("band drawing magnification", Role::Plain),
            _ => return None,
        };
        return meaning(label, "tolerances", role);
    }
    let (field, part) = match rest.rsplit_once('.') {
        Some((f, p)) if ["tol", "plus", "minus", "upper", "lower", "cp", "k"].contains(&p) => (f, p),
        _ => (rest, "tol"),
    };
    let label = match part {
        "tol" => format!("± {field}"),
        "plus" => format!("{field} +"),
        "minus" => format!("{field} −"),
        "cp" => format!("{field} Cp"),
        other => format!("{field} {other}"),
    };
    let degrees = field.trim_end_matches(|c: char| c == ']' || c.is_ascii_digit() || c == '[').ends_with("_deg");
    let role = match part {
        "cp" | "k" => Role::Plain,
        "upper" | "lower" => Role::Coordinate,
        _ => Role::Length,
    };
    let role = if degrees && role != Role::Plain { Role::Plain } else { role };
    meaning(label, "tolerances", role)
}

/// Every number in `value`, depth first in the table's order: (`--set` path, value,
/// integer).
fn numbers(prefix: &str, value: &toml::Value, out: &mut Vec<(String, f64, bool)>) {
    match value {
        toml::Value::Integer(i) => out.push((prefix.to_string(), *i as f64, true)),
        toml::Value::Float(f) => out.push((prefix.to_string(), *f, false)),
        toml::Value::Array(items) => {
            for (i, v) in items.iter().enumerate() {
                numbers(&format!("{prefix}[{i}]"), v, out);
            }
        }
        toml::Value::Table(t) => {
            for (k, v) in t {
                let path = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
                numbers(&path, v, out);
            }
        }
        _ => {}
    }
}

fn unit(role: Role, length: &str) -> &str {
    match role {
        Role::Length | Role::Coordinate => length,
        Role::Angle => "°",
        Role::AngularVelocity => "rad/s",
        Role::AngularAcceleration => "rad/s²",
        Role::Time => "s",
        Role::Mass => "kg",
        Role::Inertia => "kg·m²",
        Role::Force => "N",
        Role::Torque => "N·m",
        Role::Gravity => "m/s²",
        Role::Count | Role::Plain => "",
    }
}

/// The slider's range for a value of this role: a length from half to one and a half times
/// itself, an angle ±180° about it, a coordinate ± its size (or ±1 about 0), a count from 1
/// to twice itself.
fn range(role: Role, v: f64, integer: bool) -> (f64, f64) {
    let half = 0.5 * v.abs();
    match role {
        Role::Angle => (v - 180.0, v + 180.0),
        Role::Count if integer => (1.0_f64.min(v), (2.0 * v).max(v + 10.0)),
        Role::Length | Role::Mass | Role::Inertia | Role::Count | Role::Time if v > 0.0 => (v - half, v + half),
        _ if v == 0.0 => (-1.0, 1.0),
        _ => (v - 2.0 * half, v + 2.0 * half),
    }
}

/// `[i]` of a path's last step as x or y.
fn xy(path: &str) -> &'static str {
    if path.ends_with("[1]") { "y" } else { "x" }
}

/// The leading index of `prefix[i]...` in `path`.
fn index_after(path: &str, prefix: &str) -> Option<usize> {
    path.strip_prefix(prefix)?.strip_prefix('[')?.split(']').next()?.parse().ok()
}

/// A synthesis scene's requirement and free choices (docs/synthesis.md): what the page's
/// sliders change (ψ, K, H, the positions) to watch the construction follow.
fn synthesis(path: &str) -> Option<Meaning> {
    let need = "requirement";
    let free = "free choices";
    match path {
        "psi_deg" => meaning("rocker swing ψ", need, Role::Angle),
        "time_ratio" => meaning("time ratio K", need, Role::Plain),
        "stroke" => meaning("stroke H", need, Role::Length),
        "rocker" => meaning("rocker CB", need, Role::Length),
        "crank" => meaning("crank O1A", need, Role::Length),
        "ground" => meaning("ground O1C (O1O3)", free, Role::Length),
        "extreme_to_ground_deg" => meaning("ground line to an extreme", free, Role::Angle),
        "offset" => meaning("offset e", free, Role::Length),
        "link" => meaning("link BE", free, Role::Length),
        "ram_height" => meaning("ram guide's height", free, Role::Coordinate),
        "omega1" => meaning("ω1 of the design", "motion", Role::AngularVelocity),
        "a1[0]" | "a1[1]" => meaning(format!("A1 {}", xy(path)), free, Role::Coordinate),
        "b1[0]" | "b1[1]" => meaning(format!("B1 {}", xy(path)), free, Role::Coordinate),
        "bisector_distance[0]" => meaning("O1 along A's bisector", free, Role::Coordinate),
        "bisector_distance[1]" => meaning("C along B's bisector", free, Role::Coordinate),
        "x_range[0]" => meaning("x from", need, Role::Plain),
        "x_range[1]" => meaning("x to", need, Role::Plain),
        "input_deg[0]" => meaning("φ at x from", need, Role::Angle),
        "input_deg[1]" => meaning("φ at x to", need, Role::Angle),
        "output_deg[0]" => meaning("ψ at x from", need, Role::Angle),
        "output_deg[1]" => meaning("ψ at x to", need, Role::Angle),
        _ => {
            if let Some(i) = index_after(path, "precision_x") {
                return meaning(format!("precision point x{}", i + 1), free, Role::Plain);
            }
            let i = index_after(path, "positions")?;
            let rest = path.split_once(']').map_or("", |(_, r)| r);
            match rest {
                ".at[0]" | ".at[1]" => meaning(format!("P{} {}", i + 1, xy(rest)), need, Role::Coordinate),
                ".angle_deg" => meaning(format!("P{} line's angle", i + 1), need, Role::Angle),
                _ => None,
            }
        }
    }
}

fn fourbar(path: &str, table: &toml::Table) -> Option<Meaning> {
    let link_of = |k: &str| match k {
        "crank" => "crank",
        "AB" => "coupler AB",
        "BM" => "coupler BM",
        _ => "rocker",
    };
    match path {
        "o1[0]" | "o1[1]" => meaning(format!("O1 {}", xy(path)), "ground pivots", Role::Coordinate),
        "c[0]" | "c[1]" => meaning(format!("C {}", xy(path)), "ground pivots", Role::Coordinate),
        "l1" => meaning("crank O1A", "crank", Role::Length),
        "l_ab" => meaning("coupler AB", "coupler", Role::Length),
        "l_bm" => meaning("coupler BM", "coupler", Role::Length),
        "alpha_deg" => meaning("coupler angle ABM", "coupler", Role::Angle),
        "l_bc" => meaning("rocker BC", "rocker", Role::Length),
        "omega1" => meaning("ω1", "motion", Role::AngularVelocity),
        "epsilon1" => meaning("ε1", "motion", Role::AngularAcceleration),
        "phi1_deg.from" => meaning("φ1 from", "motion", Role::Angle),
        "phi1_deg.to" => meaning("φ1 to", "motion", Role::Angle),
        "phi1_deg.step" => meaning("φ1 step", "motion", Role::Plain),
        "dynamics.g" => meaning("g (down)", "masses and gravity", Role::Gravity),
        "dynamics.g[0]" | "dynamics.g[1]" => meaning(format!("g {}", xy(path)), "masses and gravity", Role::Gravity),
        "dynamics.m1" => meaning("crank mass m1", "masses and gravity", Role::Mass),
        "dynamics.m21" => meaning("coupler AB mass m21", "masses and gravity", Role::Mass),
        "dynamics.m22" => meaning("coupler BM mass m22", "masses and gravity", Role::Mass),
        "dynamics.m3" => meaning("rocker mass m3", "masses and gravity", Role::Mass),
        _ => {
            if let Some(i) = index_after(path, "dynamics.force") {
                let at = table
                    .get("dynamics")
                    .and_then(|d| d.get("force"))
                    .and_then(|f| f.get(i))
                    .and_then(|f| f.get("at"))
                    .and_then(toml::Value::as_str)
                    .unwrap_or("?");
                let who = format!("force {} at {at}", i + 1);
                let rest = path.split_once(']').map_or("", |(_, r)| r);
                return match rest {
                    ".value[0]" => meaning(format!("{who}: Fx"), "loads", Role::Force),
                    ".value[1]" => meaning(format!("{who}: Fy"), "loads", Role::Force),
                    ".phi1_deg[0]" => meaning(format!("{who}: from φ1"), "loads", Role::Angle),
                    ".phi1_deg[1]" => meaning(format!("{who}: to φ1"), "loads", Role::Angle),
                    _ => None,
                };
            }
            if let Some(i) = index_after(path, "dynamics.load") {
                let rest = path.split_once(']').map_or("", |(_, r)| r);
                let who = format!("load {}", i + 1);
                return match rest {
                    ".at[0]" | ".at[1]" => meaning(format!("{who}: at {}", xy(rest)), "loads", Role::Coordinate),
                    ".force[0]" | ".force[1]" => meaning(format!("{who}: F{}", xy(rest)), "loads", Role::Force),
                    ".torque" => meaning(format!("{who}: torque"), "loads", Role::Torque),
                    ".phi1_deg[0]" => meaning(format!("{who}: from φ1"), "loads", Role::Angle),
                    ".phi1_deg[1]" => meaning(format!("{who}: to φ1"), "loads", Role::Angle),
                    _ => None,
                };
            }
            let rest = path.strip_prefix("dynamics.")?;
            let (link, field) = rest.split_once('.')?;
            let who = link_of(link);
            match field {
                "centroid[0]" | "centroid[1]" => {
                    meaning(format!("{who}: centroid offset {}", xy(field)), "masses and gravity", Role::Coordinate)
                }
                "inertia" => meaning(format!("{who}: J"), "masses and gravity", Role::Inertia),
                _ => None,
            }
        }
    }
}

/// The name of `[[body]]` number `i`, or `body i+1`.
fn body_name(table: &toml::Table, i: usize) -> String {
    table
        .get("body")
        .and_then(|b| b.get(i))
        .and_then(|b| b.get("name"))
        .and_then(toml::Value::as_str)
        .map_or_else(|| format!("body {}", i + 1), str::to_string)
}

/// The name of the `[[KEY]]` item `i` (its `name`, else `KEY i+1`).
fn item_name(table: &toml::Table, key: &str, i: usize) -> String {
    table
        .get(key)
        .and_then(|b| b.get(i))
        .and_then(|b| b.get("name"))
        .and_then(toml::Value::as_str)
        .map_or_else(|| format!("{key} {}", i + 1), str::to_string)
}

fn linkage(path: &str, table: &toml::Table) -> Option<Meaning> {
    match path {
        "time.from" => return meaning("t from", "motion", Role::Time),
        "time.to" => return meaning("t to", "motion", Role::Time),
        "time.steps" => return meaning("steps", "motion", Role::Count),
        "dynamics.g[0]" | "dynamics.g[1]" => return meaning(format!("g {}", xy(path)), "gravity", Role::Gravity),
        _ => {}
    }
    if let Some(rest) = path.strip_prefix("ground.points.") {
        let name = rest.split('[').next()?;
        return meaning(format!("{name} {}", xy(rest)), "ground", Role::Coordinate);
    }
    if let Some(i) = index_after(path, "body") {
        let body = body_name(table, i);
        let rest = path.split_once(']').map_or("", |(_, r)| r);
        if let Some(point) = rest.strip_prefix(".points.") {
            return body_point(table, i, &body, point);
        }
        return match rest {
            ".at[0]" | ".at[1]" => detail(format!("{body}: placed at {} (a guess)", xy(rest)), body, Role::Coordinate),
            ".angle_deg" => detail(format!("{body}: placed at angle (a guess)"), body, Role::Angle),
            ".mass" => meaning(format!("{body}: mass"), body, Role::Mass),
            ".centroid[0]" | ".centroid[1]" => {
                meaning(format!("{body}: centroid {}", xy(rest)), body, Role::Coordinate)
            }
            ".inertia" => meaning(format!("{body}: J"), body, Role::Inertia),
            _ => None,
        };
    }
    if let Some(i) = index_after(path, "joint") {
        let joint = item_name(table, "joint", i);
        return path.ends_with(".prismatic.angle_deg").then(|| Meaning {
            label: format!("joint {joint}: locked angle"),
            group: "joints".into(),
            role: Role::Angle,
            detail: false,
        });
    }
    if let Some(i) = index_after(path, "load") {
        let load = item_name(table, "load", i);
        let rest = path.split_once(']').map_or("", |(_, r)| r);
        return match rest {
            ".force[0]" | ".force[1]" => meaning(format!("load {load}: F{}", xy(rest)), "loads", Role::Force),
            ".torque" => meaning(format!("load {load}: torque"), "loads", Role::Torque),
            ".t[0]" => meaning(format!("load {load}: from t"), "loads", Role::Time),
            ".t[1]" => meaning(format!("load {load}: to t"), "loads", Role::Time),
            _ => None,
        };
    }
    None
}

/// A body point's coordinate (`P[0]`, `P[1]` in body coordinates): a link written as its
/// first point at the origin and this one on the x axis names the x its length (`crank
/// OA`); other points name their body coordinates.
fn body_point(table: &toml::Table, i: usize, body: &str, point: &str) -> Option<Meaning> {
    let name = point.split('[').next()?;
    let points = table.get("body")?.get(i)?.get("points")?.as_table()?;
    let coords = |v: &toml::Value| -> Option<(f64, f64)> {
        let a = v.as_array()?;
        let f = |x: &toml::Value| x.as_float().or_else(|| x.as_integer().map(|i| i as f64));
        Some((f(a.first()?)?, f(a.get(1)?)?))
    };
    let (first, origin) = points.iter().next().map(|(n, v)| (n.as_str(), coords(v)))?;
    let here = coords(points.get(name)?)?;
    if name == first && origin == Some((0.0, 0.0)) {
        // The origin of the body's frame: where the others are measured from.
        return detail(format!("{body}: {name} {} (its frame's origin)", xy(point)), body, Role::Coordinate);
    }
    let on_axis = origin == Some((0.0, 0.0)) && name != first && here.1 == 0.0;
    if on_axis && point.ends_with("[0]") {
        return meaning(format!("{body} {first}{name}"), body, Role::Length);
    }
    let axis = if on_axis { format!("{name} off {first}{name}") } else { format!("{name} {}", xy(point)) };
    meaning(format!("{body}: {axis}"), body, Role::Coordinate)
}

fn triad(path: &str) -> Option<Meaning> {
    let pivot = |i: &str| meaning(format!("O{i} {}", xy(path)), "ground pivots", Role::Coordinate);
    match path {
        "o1[0]" | "o1[1]" => pivot("1"),
        "o2[0]" | "o2[1]" => pivot("2"),
        "o3[0]" | "o3[1]" => pivot("3"),
        "r[0]" => meaning("R1 (O1A1)", "radii", Role::Length),
        "r[1]" => meaning("R2 (O2A2)", "radii", Role::Length),
        "r[2]" => meaning("R3 (O3A3)", "radii", Role::Length),
        "l12" => meaning("triangle A1A2", "triangle", Role::Length),
        "l23" => meaning("triangle A2A3", "triangle", Role::Length),
        "l13" => meaning("triangle A1A3", "triangle", Role::Length),
        "mode" => meaning("assembly mode drawn", "solution", Role::Count),
        "pattern.phi1_start_deg" => meaning("pattern method: φ1 start", "solution", Role::Angle),
        "pattern.step_deg" => meaning("pattern method: step", "solution", Role::Plain),
        "pattern.tol" => meaning("pattern method: tolerance", "solution", Role::Plain),
        "pattern.max_iterations" => meaning("pattern method: iterations", "solution", Role::Count),
        "newton.max_iterations" => meaning("Newton: iterations", "solution", Role::Count),
        _ => None,
    }
}

fn chain(path: &str) -> Option<Meaning> {
    if let Some(i) = index_after(path, "W") {
        return meaning(format!("W{} (dimension)", i + 1), "dimensions", Role::Coordinate);
    }
    if let Some(i) = index_after(path, "B") {
        return meaning(format!("B{} (its base)", i + 1), "dimensions", Role::Coordinate);
    }
    if path == "tol" {
        return meaning("tolerance ±", "dimensions", Role::Plain);
    }
    if let Some(i) = index_after(path, "tol") {
        return meaning(format!("W{} tolerance ±", i + 1), "dimensions", Role::Plain);
    }
    if let Some(i) = index_after(path, "dependent") {
        let end = if path.ends_with("[1]") { "to" } else { "from" };
        return meaning(format!("Z{}: {end}", i + 1), "dependent dimensions", Role::Coordinate);
    }
    if let Some(i) = index_after(path, "dimension") {
        let rest = path.split_once(']').map_or("", |(_, r)| r);
        let who = format!("dimension {}", i + 1);
        return match rest {
            ".nominal" => meaning(format!("{who}: nominal"), "dimensions", Role::Coordinate),
            ".tol" => meaning(format!("{who}: ±"), "dimensions", Role::Plain),
            ".upper" => meaning(format!("{who}: upper deviation"), "dimensions", Role::Plain),
            ".lower" => meaning(format!("{who}: lower deviation"), "dimensions", Role::Plain),
            _ => None,
        };
    }
    match path {
        "stackup.mrss_factor" => meaning("modified RSS factor", "stack-up", Role::Plain),
        "stackup.samples" => meaning("Monte Carlo samples", "stack-up", Role::Count),
        "stackup.seed" => meaning("random seed", "stack-up", Role::Count),
        "stackup.bins" => meaning("histogram bins", "stack-up", Role::Count),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(text: &str) -> Vec<Parameter> {
        parameters(&text.parse().unwrap())
    }

    fn find<'a>(ps: &'a [Parameter], path: &str) -> &'a Parameter {
        ps.iter().find(|p| p.path == path).unwrap_or_else(|| panic!("{path}"))
    }

    #[test]
    fn a_four_bars_numbers_are_named_by_link_with_units() {
        let ps = params(include_str!("../../templates/fourbar-chebyshev.toml"));
        let l1 = find(&ps, "l1");
        assert_eq!((l1.label.as_str(), l1.unit.as_str(), l1.group.as_str()), ("crank O1A", "m", "crank"));
        assert!((l1.min - 0.02).abs() < 1e-15 && (l1.max - 0.06).abs() < 1e-15, "{l1:?}");
        let w = find(&ps, "omega1");
        assert_eq!((w.label.as_str(), w.unit.as_str()), ("ω1", "rad/s"));
        let c = find(&ps, "c[1]");
        assert_eq!((c.label.as_str(), c.unit.as_str()), ("C y", "m"));
        let f = find(&ps, "dynamics.force[0].value[1]");
        assert_eq!((f.label.as_str(), f.unit.as_str()), ("force 1 at M: Fy", "N"));
        assert_eq!(find(&ps, "alpha_deg").unit, "°");
        assert!(ps.iter().all(|p| p.label != p.path), "every number named: {ps:?}");
    }

    #[test]
    fn a_linkages_link_lengths_and_points_are_named_in_their_body() {
        let ps = params(include_str!("../../templates/slider-crank.toml"));
        let a = find(&ps, "body[0].points.A[0]");
        assert_eq!((a.label.as_str(), a.unit.as_str(), a.group.as_str()), ("crank OA", "mm", "crank"));
        assert_eq!(find(&ps, "body[0].points.A[1]").label, "crank: A off OA");
        // The frame's origin and the starting placement are details, folded away.
        assert!(find(&ps, "body[0].points.O[0]").detail && find(&ps, "body[1].at[0]").detail);
        assert!(!find(&ps, "body[0].points.A[0]").detail && !find(&ps, "body[1].mass").detail);
        assert_eq!(find(&ps, "body[1].mass").unit, "kg");
        assert_eq!(find(&ps, "time.steps").label, "steps");
        assert_eq!(find(&ps, "ground.points.G2[0]").label, "G2 x");
        let ps = params(include_str!("../../templates/triad-driven.toml"));
        assert_eq!(find(&ps, "body[4].points.A3[1]").label, "triangle: A3 y");
        assert_eq!(find(&ps, "body[4].points.A2[0]").label, "triangle A1A2");
    }

    #[test]
    fn every_template_number_has_a_name() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates");
        for entry in std::fs::read_dir(dir).unwrap() {
            let file = entry.unwrap().path();
            for p in params(&std::fs::read_to_string(&file).unwrap()) {
                assert_ne!(p.label, p.path, "{}: {} has no name", file.display(), p.path);
                assert!(p.min <= p.value && p.value <= p.max, "{}: {} outside its range", file.display(), p.path);
            }
        }
    }
}
