//! Tolerance studies in a run (issue 34): the `[tolerances]` of a scene become a
//! [`Study`] (the linear stack-up and the Monte Carlo over the whole motion, from
//! `solve::tolerance`), and the study becomes tables, the JSON summary's `tolerances`, the
//! report, and the figures of `figure::tolerances`. A study run in shards (`--shard K/N`)
//! writes its partial statistics instead; `mechdraw merge` adds the shards into the single
//! run's study ([`merge_shards`]). docs/tolerances.md documents the files.

use std::ops::Range;

use serde_json::{Value, json};

use crate::geom::{Point, Vector, perp};
use crate::report::{self, Csv};
use crate::scene::Units;
use crate::scene::tolerance::Settings;
use crate::solve::tolerance::fourbar::{FourbarModel, FourbarOutput};
use crate::solve::tolerance::monte_carlo::{self, chunk_count};
use crate::solve::tolerance::{
    Component, Dimension, Linear, Model, MonteCarlo, Projection, Summary, dead_points, linear_all, ranges, verdicts,
};

/// The abscissa of a study: the scene's position column.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Axis {
    /// The CSV column (`phi1_deg`, `t`).
    pub column: &'static str,
    /// Its symbol and unit on the diagrams (`φ1`, `°`).
    pub symbol: &'static str,
    /// Unit.
    pub unit: &'static str,
    /// The value at each position.
    pub values: Vec<f64>,
    /// Whether the positions are a motion's (a triad's are its assembly modes: no path, no
    /// band against a position).
    pub motion: bool,
}

/// A watched point's nominal path, for the band drawing.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct WatchedPath {
    /// The point's name.
    pub name: String,
    /// Its nominal position at each position of the motion.
    pub points: Vec<Point>,
    /// The unit normal of the path there (zero where undefined).
    pub normals: Vec<Vector>,
    /// The index of its `normal` component.
    pub normal: usize,
}

/// A tolerance study of one scene: what the tables, the summary and the figures show.
#[derive(Debug, Clone)]
pub(crate) struct Study {
    /// The scene's name and units.
    pub name: String,
    /// Length units.
    pub units: Units,
    /// The positions.
    pub axis: Axis,
    /// Toleranced dimensions.
    pub dims: Vec<Dimension>,
    /// Reported components.
    pub comps: Vec<Component>,
    /// What each component measures.
    pub quantities: Vec<Quantity>,
    /// Each position's and component's nominal value (0 for a deviation component).
    pub nominal: Vec<f64>,
    /// The linear stack-up per position (`None` at a dead point), per component.
    pub linear: Vec<Option<Vec<Linear>>>,
    /// Each position's dead-point note.
    pub dead: Vec<Option<String>>,
    /// The Monte Carlo's counts (this run's share of the chunks).
    pub mc: MonteCarlo,
    /// The settings.
    pub settings: Settings,
    /// The watched points' paths.
    pub paths: Vec<WatchedPath>,
    /// The mechanism at its first position, as segments (context on the band drawing).
    pub sketch: Vec<(Point, Point)>,
    /// Each dimension's name on the charts (the field path, or a shorter name of the same
    /// field: a linkage's `rocker.B[0]` for `body[2].points.B[0]`).
    pub labels: Vec<String>,
    /// A triad's pose in each of its modes (the zones' panels, zones not yet filled in);
    /// empty for a motion.
    pub poses: Vec<crate::figure::tolerances::ZonePanel>,
}

/// What a component measures: its unit on the diagrams.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Quantity {
    /// A length (a point's coordinate or deviation), scene units.
    Length,
    /// An angle, degrees.
    Angle,
    /// A velocity, scene units/s.
    Velocity,
    /// An acceleration, scene units/s².
    Acceleration,
    /// An angular velocity, rad/s.
    AngularVelocity,
    /// An angular acceleration, rad/s².
    AngularAcceleration,
}

impl Quantity {
    /// Whether it is a vector's (two channels: x, y).
    fn vector(self) -> bool {
        matches!(self, Quantity::Length | Quantity::Velocity | Quantity::Acceleration)
    }
}

/// A watched output as the components see it: its name, what it measures, and for a
/// vector of a point on a path the unit tangents of its nominal path (one per position).
struct Watched {
    name: String,
    quantity: Quantity,
    tangents: Option<Vec<Vector>>,
}

/// The components of watched outputs (channels in their order, 2 for a point, 1 for an
/// angle; `nominal` the model's channel values, position-major): a point's x, y, normal and
/// along; an angle's value.
fn components(
    watched: &[Watched],
    nominal: &[f64],
    channels: usize,
) -> (Vec<Component>, Vec<Quantity>, Vec<WatchedPath>) {
    let mut comps = Vec::new();
    let mut quantities = Vec::new();
    let mut paths = Vec::new();
    let mut ch = 0;
    let np = nominal.len() / channels.max(1);
    for w in watched {
        let name = w.name.as_str();
        let comp = |part: &'static str, absolute, projection| Component {
            name: format!("{name}.{part}"),
            output: name.to_string(),
            part,
            absolute,
            projection,
        };
        let before = comps.len();
        if !w.quantity.vector() {
            comps.push(comp("value", true, Projection::Channel(ch)));
            quantities.push(w.quantity);
            ch += 1;
            continue;
        }
        let Some(tangents) = &w.tangents else {
            // A point with no path (a triad's vertex): its coordinates only.
            comps.push(comp("x", true, Projection::Channel(ch)));
            comps.push(comp("y", true, Projection::Channel(ch + 1)));
            quantities.extend([w.quantity; 2]);
            ch += 2;
            continue;
        };
        let normals: Vec<Vector> = tangents.iter().map(|t| perp(*t)).collect();
        comps.push(comp("x", true, Projection::Channel(ch)));
        comps.push(comp("y", true, Projection::Channel(ch + 1)));
        // A point's position has a path to draw its band along; its rates do not.
        if w.quantity == Quantity::Length {
            paths.push(WatchedPath {
                name: name.to_string(),
                points: (0..np)
                    .map(|k| Point::new(nominal[k * channels + ch], nominal[k * channels + ch + 1]))
                    .collect(),
                normals: normals.clone(),
                normal: comps.len(),
            });
        }
        comps.push(comp("normal", false, Projection::Along { x: ch, y: ch + 1, dirs: normals }));
        comps.push(comp("along", false, Projection::Along { x: ch, y: ch + 1, dirs: tangents.clone() }));
        quantities.extend(std::iter::repeat_n(w.quantity, comps.len() - before));
        ch += 2;
    }
    (comps, quantities, paths)
}

/// The four-bar's components: a point's x, y, normal and along (its position's, velocity's
/// or acceleration's, about the point's path); an angle's or a link's rate's value.
fn fourbar_components(model: &FourbarModel) -> (Vec<Component>, Vec<Quantity>, Vec<WatchedPath>) {
    let watched: Vec<Watched> = model
        .outputs()
        .iter()
        .map(|o| Watched {
            name: o.name().to_string(),
            quantity: match o {
                FourbarOutput::Point(_) => Quantity::Length,
                FourbarOutput::Phi2 | FourbarOutput::Phi3 => Quantity::Angle,
                FourbarOutput::Velocity(_) => Quantity::Velocity,
                FourbarOutput::Acceleration(_) => Quantity::Acceleration,
                FourbarOutput::Omega2 | FourbarOutput::Omega3 => Quantity::AngularVelocity,
                FourbarOutput::Eps2 | FourbarOutput::Eps3 => Quantity::AngularAcceleration,
            },
            tangents: o.point().map(|p| model.tangents(p)),
        })
        .collect();
    components(&watched, model.nominal(), model.channels())
}

/// The nominal value of every component at every position (0 for deviation components).
fn nominal_values<M: Model>(model: &M, nominal_channels: &[f64], comps: &[Component]) -> Vec<f64> {
    let ch = model.channels();
    let mut out = Vec::with_capacity(model.positions() * comps.len());
    for k in 0..model.positions() {
        for c in comps {
            out.push(match (&c.projection, c.absolute) {
                (Projection::Channel(i), true) => nominal_channels[k * ch + i],
                _ => 0.0,
            });
        }
    }
    out
}

/// What every kind's study computes alike: the linear stack-up, the dead-point notes, the
/// Monte Carlo (`chunks` of it; all of them for `None`) and the components' nominal values.
struct Analysis {
    dims: Vec<Dimension>,
    linear: Vec<Option<Vec<Linear>>>,
    dead: Vec<Option<String>>,
    mc: MonteCarlo,
    nominal: Vec<f64>,
}

impl Analysis {
    /// A study of it (its name, axis, components and figures' parts still to be set).
    fn into(self, settings: Settings) -> Study {
        Study {
            name: String::new(),
            units: Units::Si,
            axis: Axis { column: "", symbol: "", unit: "", values: Vec::new(), motion: true },
            dims: self.dims,
            comps: Vec::new(),
            quantities: Vec::new(),
            nominal: self.nominal,
            linear: self.linear,
            dead: self.dead,
            mc: self.mc,
            settings,
            paths: Vec::new(),
            sketch: Vec::new(),
            labels: Vec::new(),
            poses: Vec::new(),
        }
    }
}

/// The [`Analysis`] of `model` (nominal channel values `nominal`).
fn analyse<M: crate::solve::tolerance::Sensitive>(
    model: &M,
    nominal: &[f64],
    dims: &[Dimension],
    comps: &[Component],
    s: &Settings,
    chunks: Option<Range<u64>>,
) -> Analysis {
    let linear = linear_all(model, dims, comps);
    let dead = dead_points(model, dims, &linear);
    let rs = ranges(&linear, comps.len());
    let chunks = chunks.unwrap_or(0..chunk_count(s.samples));
    let mc = monte_carlo::run(model, dims, comps, &rs, s.bins, s.samples, s.seed, chunks);
    Analysis { dims: dims.to_vec(), linear, dead, mc, nominal: nominal_values(model, nominal, comps) }
}

/// The study of a four-bar scene: `chunks` of its Monte Carlo (all of them for a whole run,
/// a shard's share, or none for a merge).
pub(crate) fn fourbar(
    scene: &crate::scene::fourbar::FourbarScene,
    positions: &[crate::solve::fourbar::Position],
    chunks: Option<Range<u64>>,
) -> Option<Study> {
    let tol = scene.tolerances.as_ref()?;
    let g = scene.spec.geometry;
    let model = FourbarModel::new(g, positions, tol.study.params.clone(), tol.outputs.clone())
        .with_crank(scene.spec.omega1, scene.spec.epsilon1);
    let (comps, quantities, paths) = fourbar_components(&model);
    let a = analyse(&model, model.nominal(), &tol.study.dims, &comps, &tol.study.settings, chunks);
    let sketch = positions.first().map(|p| vec![(g.o1, p.a), (p.a, p.b), (p.b, p.m), (g.c, p.b)]).unwrap_or_default();
    let axis = Axis {
        column: "phi1_deg",
        symbol: "φ1",
        unit: "°",
        values: positions.iter().map(|p| p.phi1.to_degrees()).collect(),
        motion: true,
    };
    let settings = tol.study.settings.clone();
    Some(Study {
        name: scene.name.clone(),
        units: scene.units,
        axis,
        comps,
        quantities,
        paths,
        sketch,
        labels: Vec::new(),
        ..a.into(settings)
    })
}

/// The study of a linkage scene over its motion: `chunks` of its Monte Carlo (all of them
/// for a whole run, a shard's share, or none for a merge); `None` without `[tolerances]`.
pub(crate) fn linkage(
    scene: &crate::scene::linkage::LinkageScene,
    chunks: Option<Range<u64>>,
) -> Result<Option<Study>, crate::solve::tolerance::linkage::LinkageToleranceError> {
    use crate::solve::tolerance::linkage::LinkageModel;
    let Some(tol) = scene.tolerances.as_ref() else { return Ok(None) };
    let model =
        LinkageModel::new(scene.mechanism.clone(), &scene.times, tol.study.params.clone(), tol.outputs.clone())?;
    let watched: Vec<Watched> = model
        .outputs()
        .iter()
        .enumerate()
        .map(|(i, o)| Watched {
            name: o.name().to_string(),
            quantity: linkage_quantity(o),
            tangents: linkage_quantity(o).vector().then(|| model.tangents(i)),
        })
        .collect();
    let (comps, quantities, paths) = components(&watched, model.nominal(), model.channels());
    let a = analyse(&model, model.nominal(), &tol.study.dims, &comps, &tol.study.settings, chunks);
    // The mechanism at its first position: each body's outline.
    let mut sketch = Vec::new();
    if let Some(st) = model.states().first() {
        for (i, b) in model.mechanism().bodies.iter().enumerate() {
            let at = |v: Vector| Point::new(st.q[3 * i], st.q[3 * i + 1]) + crate::geom::rotate(v, st.q[3 * i + 2]);
            for w in b.points.windows(2) {
                sketch.push((at(w[0].1), at(w[1].1)));
            }
        }
    }
    let axis = Axis { column: "t", symbol: "t", unit: "s", values: scene.times.clone(), motion: true };
    let labels = tol.study.dims.iter().map(|d| chart_label(scene, &d.name)).collect();
    let settings = tol.study.settings.clone();
    Ok(Some(Study {
        name: scene.name.clone(),
        units: scene.units,
        axis,
        comps,
        quantities,
        paths,
        sketch,
        labels,
        ..a.into(settings)
    }))
}

/// The study of a triad scene in its assembly modes `modes` (as the run found them):
/// `chunks` of its Monte Carlo (all of them for a whole run, a shard's share, or none for a
/// merge); `None` without `[tolerances]`.
pub(crate) fn triad(
    scene: &crate::scene::triad::TriadScene,
    triad: &crate::solve::triad::Triad,
    modes: &[crate::solve::triad::Configuration],
    chunks: Option<Range<u64>>,
) -> Option<Study> {
    use crate::solve::tolerance::triad::{TriadModel, TriadOutput};
    let tol = scene.tolerances.as_ref()?;
    let model = TriadModel::new(*triad, modes.to_vec(), tol.study.params.clone(), tol.outputs.clone());
    let watched: Vec<Watched> = model
        .outputs()
        .iter()
        .map(|o| Watched {
            name: o.name(),
            quantity: if matches!(o, TriadOutput::Vertex(_)) { Quantity::Length } else { Quantity::Angle },
            tangents: None,
        })
        .collect();
    let (comps, quantities, paths) = components(&watched, model.nominal(), model.channels());
    let a = analyse(&model, model.nominal(), &tol.study.dims, &comps, &tol.study.settings, chunks);
    let axis = Axis {
        column: "mode",
        symbol: "mode",
        unit: "",
        values: (1..=modes.len()).map(|m| m as f64).collect(),
        motion: false,
    };
    let settings = tol.study.settings.clone();
    let poses = modes
        .iter()
        .enumerate()
        .map(|(k, c)| crate::figure::tolerances::ZonePanel {
            heading: crate::figure::triad::mode_heading(k + 1, c, false),
            pivots: triad.o,
            vertices: c.a,
            zones: Vec::new(),
        })
        .collect();
    Some(Study {
        name: scene.name.clone(),
        units: scene.units,
        axis,
        comps,
        quantities,
        paths,
        sketch: Vec::new(),
        labels: Vec::new(),
        poses,
        ..a.into(settings)
    })
}

/// What a linkage's output measures.
fn linkage_quantity(o: &crate::solve::tolerance::linkage::LinkageOutput) -> Quantity {
    use crate::solve::tolerance::linkage::LinkageOutput as O;
    match o {
        O::Point { .. } => Quantity::Length,
        O::Angle { .. } => Quantity::Angle,
        O::Velocity { .. } => Quantity::Velocity,
        O::Acceleration { .. } => Quantity::Acceleration,
        O::Omega { .. } => Quantity::AngularVelocity,
        O::Eps { .. } => Quantity::AngularAcceleration,
    }
}

/// A linkage field's name on the charts: `ground.C[0]` for `ground.points.C[0]`,
/// `rocker.B[1]` for `body[2].points.B[1]`, `slide.angle_deg` for
/// `joint[2].prismatic.angle_deg` (the scene's own names, shorter than the paths).
fn chart_label(scene: &crate::scene::linkage::LinkageScene, path: &str) -> String {
    let indexed = |rest: &str| -> Option<(usize, String)> {
        let (i, tail) = rest.split_once(']')?;
        Some((i.parse().ok()?, tail.to_string()))
    };
    let short = if let Some(rest) = path.strip_prefix("ground.points.") {
        Some(format!("ground.{rest}"))
    } else if let Some((i, tail)) = path.strip_prefix("body[").and_then(indexed) {
        let body = scene.mechanism.bodies.get(i).map(|b| b.name.as_str());
        body.zip(tail.strip_prefix(".points.")).map(|(b, p)| format!("{b}.{p}"))
    } else if let Some((j, tail)) = path.strip_prefix("joint[").and_then(indexed) {
        let joint = scene.mechanism.joints.get(j).map(|x| x.name.as_str());
        joint.zip(tail.strip_prefix(".prismatic.")).map(|(n, f)| format!("{n}.{f}"))
    } else {
        None
    };
    short.unwrap_or_else(|| path.to_string())
}

impl Study {
    /// Adds the study's tables, summary, report and figures to a run's extras; returns its
    /// warnings.
    pub fn add_to(&self, extras: &mut super::products::Extras) -> Vec<String> {
        let notes = self.notes();
        extras.tables.push(super::products::Table { suffix: "-tolerances".into(), csv: self.table(&notes) });
        extras.tables.push(super::products::Table { suffix: "-contributions".into(), csv: self.contributions() });
        if let Value::Object(m) = &mut extras.summary {
            m.insert("tolerances".into(), self.summary_json(&notes));
        }
        if !extras.report.is_empty() && !extras.report.ends_with('\n') {
            extras.report.push('\n');
        }
        extras.report.push_str(&self.report(&notes));
        if !self.paths.is_empty() {
            extras
                .sheets
                .push(super::products::Sheet { suffix: "tolerance-band".into(), drawing: self.band_drawing() });
        }
        if !self.poses.is_empty() {
            extras
                .sheets
                .push(super::products::Sheet { suffix: "tolerance-zones".into(), drawing: self.zones_drawing() });
        }
        for c in (0..self.comps.len()).filter(|_| self.axis.motion) {
            let name = &self.comps[c].name;
            extras.diagrams.push(super::products::Diagram {
                stem: format!("{name}-band"),
                drawing: self.band_diagram(c),
                // No marker on the live page: a band is two edges per curve.
                track: Vec::new(),
            });
        }
        for c in self.headline() {
            if let Some(drawing) = self.pareto(c) {
                let stem = format!("{}-pareto", self.comps[c].name);
                extras.diagrams.push(super::products::Diagram { stem, drawing, track: Vec::new() });
            }
        }
        self.warnings(&notes)
    }

    /// Position `k`'s value as the texts write it (a mode's number as a whole number).
    fn position_value(&self, k: usize) -> String {
        if self.axis.motion { short(self.axis.values[k]) } else { format!("{}", self.axis.values[k]) }
    }

    /// Position `k`'s value in the JSON: a number, a mode's as an integer (`1`, not `1.0`).
    fn position_json(&self, k: usize) -> Value {
        let v = self.axis.values[k];
        if self.axis.motion { json!(v) } else { json!(v as u64) }
    }

    /// The position's label on the figures and in the texts (`φ1 = 123°`, `t = 0.09 s`,
    /// `mode = 2`).
    fn at_label(&self, k: usize) -> String {
        let gap = if self.axis.unit == "°" || self.axis.unit.is_empty() { "" } else { " " };
        format!("{} = {}{gap}{}", self.axis.symbol, self.position_value(k), self.axis.unit)
    }

    /// The band drawing of the watched points.
    fn band_drawing(&self) -> crate::draw::Drawing {
        use crate::figure::tolerances::{BandPath, band_drawing};
        let nc = self.comps.len();
        let paths: Vec<BandPath> = self
            .paths
            .iter()
            .map(|p| {
                let c = p.normal;
                BandPath {
                    name: p.name.clone(),
                    nominal: p.points.clone(),
                    normals: p.normals.clone(),
                    rss: (0..self.positions()).map(|k| self.linear[k].as_ref().map(|l| l[c].rss)).collect(),
                    mc: (0..self.positions())
                        .map(|k| self.mc.tallies[k * nc + c].summary().map(|s| (s.p_low, s.p_high)))
                        .collect(),
                    worst: self.worst(c).map(|k| (k, self.at_label(k))),
                }
            })
            .collect();
        let units = match self.units {
            Units::Si => crate::figure::shared::vocab::ModelUnits::SI,
            Units::Mm => crate::figure::shared::vocab::ModelUnits::MM,
        };
        let title = format!(
            "{}: tolerance bands of {}",
            self.name,
            self.paths.iter().map(|p| p.name.as_str()).collect::<Vec<_>>().join(", ")
        );
        band_drawing(&paths, &self.sketch, units, self.settings.magnification, &title)
    }

    /// The zones drawing of a triad's vertices in each mode: the RSS ellipse from the
    /// linear covariance of x and y (Σ s_x,i·s_y,i·σ_i² over the dimensions), the Monte
    /// Carlo's percentile box of x and y.
    fn zones_drawing(&self) -> crate::draw::Drawing {
        use crate::figure::tolerances::{Zone, zones_drawing};
        let index = |name: &str| self.comps.iter().position(|c| c.name == name);
        let vertices: Vec<(String, usize, usize)> = self
            .comps
            .iter()
            .filter(|c| c.part == "x")
            .filter_map(|c| Some((c.output.clone(), index(&c.name)?, index(&format!("{}.y", c.output))?)))
            .collect();
        let nc = self.comps.len();
        let panels: Vec<_> = self
            .poses
            .iter()
            .enumerate()
            .map(|(k, pose)| {
                let zones = vertices
                    .iter()
                    .filter_map(|(name, cx, cy)| {
                        let l = self.linear[k].as_ref()?;
                        let (lx, ly) = (&l[*cx], &l[*cy]);
                        let mut cov = [0.0; 3];
                        for ((d, sx), sy) in self.dims.iter().zip(&lx.shares).zip(&ly.shares) {
                            let v = d.sigma() * d.sigma();
                            cov[0] += sx.sensitivity * sx.sensitivity * v;
                            cov[1] += sx.sensitivity * sy.sensitivity * v;
                            cov[2] += sy.sensitivity * sy.sensitivity * v;
                        }
                        let mc = self.mc.tallies[k * nc + cx]
                            .summary()
                            .zip(self.mc.tallies[k * nc + cy].summary())
                            .map(|(x, y)| (Vector::new(x.p_low, y.p_low), Vector::new(x.p_high, y.p_high)));
                        let at = Point::new(self.nominal[k * nc + cx], self.nominal[k * nc + cy]);
                        let zone = Zone {
                            name: name.clone(),
                            at,
                            shift: Vector::new(lx.shift, ly.shift),
                            covariance: cov,
                            mc,
                        };
                        cov.iter().all(|v| v.is_finite()).then_some(zone)
                    })
                    .collect();
                crate::figure::tolerances::ZonePanel { zones, ..pose.clone() }
            })
            .collect();
        let units = match self.units {
            Units::Si => crate::figure::shared::vocab::ModelUnits::SI,
            Units::Mm => crate::figure::shared::vocab::ModelUnits::MM,
        };
        let title = vec![format!(
            "{}: tolerance zones of {} in each assembly mode",
            self.name,
            vertices.iter().map(|v| v.0.as_str()).collect::<Vec<_>>().join(", ")
        )];
        zones_drawing(&panels, units, self.settings.magnification, &title)
    }

    /// Component `c`'s deviations in the diagrams' unit: (factor, unit): lengths in mm for
    /// SI scenes and in µm for mm scenes, angles in degrees.
    fn deviation_unit(&self, c: usize) -> (f64, &'static str) {
        let si = self.units == Units::Si;
        match self.quantities[c] {
            Quantity::Angle => (1.0, "°"),
            Quantity::AngularVelocity => (1.0, "rad/s"),
            Quantity::AngularAcceleration => (1.0, "rad/s²"),
            Quantity::Length => (1000.0, if si { "mm" } else { "µm" }),
            Quantity::Velocity => (1000.0, if si { "mm/s" } else { "µm/s" }),
            Quantity::Acceleration => (1000.0, if si { "mm/s²" } else { "µm/s²" }),
        }
    }

    /// Component `c`'s band diagram.
    fn band_diagram(&self, c: usize) -> crate::draw::Drawing {
        use crate::figure::tolerances::{Bands, band_diagram};
        let (f, unit) = self.deviation_unit(c);
        let nc = self.comps.len();
        let lin = |g: &dyn Fn(&Linear) -> f64| -> Vec<Option<f64>> {
            (0..self.positions()).map(|k| self.linear[k].as_ref().map(|l| f * g(&l[c]))).collect()
        };
        let comp = &self.comps[c];
        // A rate's normal and along are about its point's path.
        let whose = if self.quantities[c] == Quantity::Length { "its" } else { "the point's" };
        let what = match comp.part {
            "normal" => format!("{} normal to {whose} path", comp.output),
            "along" => format!("{} along {whose} path", comp.output),
            "value" => comp.output.clone(),
            part => format!("{}.{part}", comp.output),
        };
        band_diagram(&Bands {
            title: format!("{}: tolerance band of {what}", self.name),
            x_label: format!("{} [{}]", self.axis.symbol, self.axis.unit),
            y_label: format!("deviation of {} [{unit}]", comp.name),
            x: self.axis.values.clone(),
            shift: lin(&|l| l.shift),
            wc: lin(&|l| l.worst_case),
            rss: lin(&|l| l.rss),
            mc: (0..self.positions())
                .map(|k| self.mc.tallies[k * nc + c].summary().map(|s| (f * s.p_low, f * s.p_high)))
                .collect(),
            worst: self.worst(c).map(|k| (k, format!("widest at {}", self.at_label(k)))),
        })
    }

    /// Component `c`'s Pareto chart at its widest position (`None` without one).
    fn pareto(&self, c: usize) -> Option<crate::draw::Drawing> {
        use crate::figure::tolerances::{Contribution, pareto};
        let k = self.worst(c)?;
        let l = self.linear[k].as_ref()?;
        let list: Vec<Contribution> = self
            .dims
            .iter()
            .zip(&l[c].shares)
            .enumerate()
            .map(|(i, (d, s))| Contribution {
                dimension: self.labels.get(i).cloned().unwrap_or_else(|| d.name.clone()),
                pct_variance: s.pct_variance,
                pct_worst_case: s.pct_worst_case,
            })
            .collect();
        Some(pareto(&format!("{}: contributions to {} at {}", self.name, self.comps[c].name, self.at_label(k)), &list))
    }

    /// Number of positions.
    pub fn positions(&self) -> usize {
        self.axis.values.len()
    }

    /// The Monte Carlo statistics of component `c` at position `k`.
    pub fn summary(&self, k: usize, c: usize) -> Option<Summary> {
        self.mc.tallies[k * self.comps.len() + c].summary()
    }

    /// Where the linear result is not to be trusted, per position.
    pub fn notes(&self) -> Vec<Vec<String>> {
        verdicts(&self.dead, &self.comps, &self.linear, &self.mc, self.settings.trust)
    }

    /// Component `c`'s half spread at position `k`: the Monte Carlo's (p99.865 − p0.135)/2
    /// when it has samples there, else the RSS; `None` at a dead point without samples.
    pub fn spread(&self, k: usize, c: usize) -> Option<f64> {
        match self.summary(k, c) {
            Some(s) => Some(0.5 * (s.p_high - s.p_low)),
            None => self.linear[k].as_ref().map(|l| l[c].rss),
        }
    }

    /// The position where component `c` spreads widest ([`Study::spread`]).
    pub fn worst(&self, c: usize) -> Option<usize> {
        (0..self.positions())
            .filter_map(|k| self.spread(k, c).filter(|v| v.is_finite()).map(|v| (k, v)))
            .fold(None, |best: Option<(usize, f64)>, (k, v)| match best {
                Some((_, b)) if b >= v => best,
                _ => Some((k, v)),
            })
            .map(|(k, _)| k)
    }

    /// The components whose charts are drawn: a point's normal (its x and y when it has no
    /// path: a triad's vertex), a point's velocity's or acceleration's component along the
    /// path (the speed's, the tangential acceleration's), an angle's or a rate's value.
    pub fn headline(&self) -> Vec<usize> {
        let has_normal = |o: &str| self.comps.iter().any(|c| c.output == o && c.part == "normal");
        (0..self.comps.len())
            .filter(|&c| match (self.comps[c].part, self.quantities[c]) {
                ("normal", Quantity::Length) | ("value", _) => true,
                ("along", Quantity::Velocity | Quantity::Acceleration) => true,
                ("x" | "y", _) => !has_normal(&self.comps[c].output),
                _ => false,
            })
            .collect()
    }

    /// `<name>-tolerances.csv`: one row per position (see docs/tolerances.md).
    pub fn table(&self, notes: &[Vec<String>]) -> Csv {
        let mut header = vec![self.axis.column.to_string()];
        for c in &self.comps {
            for s in STATS {
                header.push(format!("{}.{s}", c.name));
            }
        }
        header.extend(["failed".to_string(), "linear_trusted".to_string(), "note".to_string()]);
        let mut csv = Csv::new(header);
        let num = |v: Option<f64>| v.filter(|v| v.is_finite()).map_or(String::new(), report::number);
        for (k, note) in notes.iter().enumerate().take(self.positions()) {
            let mut row = vec![report::number(self.axis.values[k])];
            for c in 0..self.comps.len() {
                row.extend(self.stats(k, c).into_iter().map(num));
            }
            row.push(self.mc.failed_at[k].to_string());
            row.push(note.is_empty().to_string());
            row.push(note.join("; "));
            csv.row_text(row);
        }
        csv
    }

    /// The values of [`STATS`] for component `c` at position `k` (absolute components'
    /// nominal, mean and percentiles as values, deviation components' as deviations).
    fn stats(&self, k: usize, c: usize) -> [Option<f64>; 9] {
        let nominal = self.nominal[k * self.comps.len() + c];
        let l = self.linear[k].as_ref().map(|l| &l[c]);
        let s = self.summary(k, c);
        [
            Some(nominal),
            l.map(|l| l.shift),
            l.map(|l| l.worst_case),
            l.map(|l| l.rss),
            l.map(|l| l.sigma),
            s.map(|s| nominal + s.mean),
            s.map(|s| s.sigma),
            s.map(|s| nominal + s.p_low),
            s.map(|s| nominal + s.p_high),
        ]
    }

    /// `<name>-contributions.csv`: one row per position, component and dimension.
    pub fn contributions(&self) -> Csv {
        let mut csv = Csv::new([
            self.axis.column,
            "component",
            "dimension",
            "sensitivity",
            "worst_case",
            "pct_worst_case",
            "pct_variance",
        ]);
        for k in 0..self.positions() {
            let Some(lin) = &self.linear[k] else { continue };
            for (c, l) in self.comps.iter().zip(lin) {
                for (d, s) in self.dims.iter().zip(&l.shares) {
                    csv.row_text([
                        report::number(self.axis.values[k]),
                        c.name.clone(),
                        d.name.clone(),
                        report::number(s.sensitivity),
                        report::number(s.worst_case),
                        report::number(s.pct_worst_case),
                        report::number(s.pct_variance),
                    ]);
                }
            }
        }
        csv
    }

    /// The summary's `tolerances` (see docs/tolerances.md).
    pub fn summary_json(&self, notes: &[Vec<String>]) -> Value {
        let opt = |v: Option<f64>| v.filter(|v| v.is_finite()).map_or(Value::Null, |v| json!(v));
        let dims: Vec<Value> = self
            .dims
            .iter()
            .map(|d| {
                json!({
                    "name": d.name, "nominal": d.nominal, "upper": d.upper, "lower": d.lower,
                    "tol": d.half(), "shift": d.mid(), "distribution": d.distribution.name(),
                    "sigma": d.sigma(),
                })
            })
            .collect();
        let comps: Vec<Value> = (0..self.comps.len())
            .map(|c| {
                let w = self.worst(c);
                json!({
                    "name": self.comps[c].name,
                    "output": self.comps[c].output,
                    "part": self.comps[c].part,
                    "worst": w.map_or(Value::Null, |k| json!({
                        self.axis.column: self.position_json(k),
                        "index": k,
                        "mc_half_spread": opt(self.spread(k, c)),
                        "wc": opt(self.linear[k].as_ref().map(|l| l[c].worst_case)),
                        "rss": opt(self.linear[k].as_ref().map(|l| l[c].rss)),
                    })),
                })
            })
            .collect();
        let positions: Vec<Value> = (0..self.positions())
            .map(|k| {
                let mut values = serde_json::Map::new();
                let mut shares = serde_json::Map::new();
                for (c, comp) in self.comps.iter().enumerate() {
                    let st = self.stats(k, c);
                    let obj: serde_json::Map<String, Value> =
                        STATS.iter().zip(st).map(|(n, v)| (n.to_string(), opt(v))).collect();
                    values.insert(comp.name.clone(), Value::Object(obj));
                    if let Some(l) = &self.linear[k] {
                        let list: Vec<Value> = self
                            .dims
                            .iter()
                            .zip(&l[c].shares)
                            .map(|(d, s)| {
                                json!({
                                    "dimension": d.name, "sensitivity": s.sensitivity, "worst_case": s.worst_case,
                                    "pct_worst_case": s.pct_worst_case, "pct_variance": s.pct_variance,
                                })
                            })
                            .collect();
                        shares.insert(comp.name.clone(), Value::Array(list));
                    }
                }
                json!({
                    self.axis.column: self.position_json(k),
                    "failed": self.mc.failed_at[k],
                    "linear_trusted": notes[k].is_empty(),
                    "notes": notes[k],
                    "values": values,
                    "contributions": shares,
                })
            })
            .collect();
        json!({
            "position": self.axis.column,
            "samples": self.settings.samples,
            "drawn": self.mc.drawn,
            "seed": self.settings.seed,
            "bins": self.settings.bins,
            "trust": self.settings.trust,
            "failed_samples": self.mc.failed_samples,
            "dimensions": dims,
            "components": comps,
            "positions": positions,
        })
    }

    /// The terminal's lines: per headline component, its worst position and bands.
    pub fn report(&self, notes: &[Vec<String>]) -> String {
        let mut out = format!(
            "tolerances: {} dimensions, {} Monte Carlo samples (seed {}), {} cannot be assembled\n",
            self.dims.len(),
            self.mc.drawn,
            self.settings.seed,
            self.mc.failed_samples
        );
        for c in self.headline() {
            let Some(k) = self.worst(c) else { continue };
            let l = self.linear[k].as_ref().map(|l| &l[c]);
            out.push_str(&format!(
                "  {}: widest at {}: WC ±{}, RSS ±{}, MC ±{}\n",
                self.comps[c].name,
                self.at_label(k),
                l.map_or("–".into(), |l| short(l.worst_case)),
                l.map_or("–".into(), |l| short(l.rss)),
                self.spread(k, c).map_or("–".into(), short),
            ));
        }
        let untrusted = notes.iter().filter(|n| !n.is_empty()).count();
        if untrusted > 0 {
            out.push_str(&format!(
                "  linear result not to be trusted at {untrusted} positions (see the note column)\n"
            ));
        }
        out
    }

    /// Warnings: samples that cannot be assembled, positions where the linear result is
    /// not to be trusted.
    pub fn warnings(&self, notes: &[Vec<String>]) -> Vec<String> {
        let mut w = Vec::new();
        if self.mc.failed_samples > 0 {
            let at: Vec<String> =
                (0..self.positions()).filter(|&k| self.mc.failed_at[k] > 0).take(5).map(|k| self.at_label(k)).collect();
            w.push(format!(
                "tolerances: {} of {} Monte Carlo samples ({:.3} %) cannot be assembled {} (first at {}); they are left out of the statistics",
                self.mc.failed_samples,
                self.mc.drawn,
                100.0 * self.mc.failed_samples as f64 / self.mc.drawn.max(1) as f64,
                if self.axis.motion { "somewhere in the motion" } else { "in some assembly mode" },
                at.join(", ")
            ));
        }
        let bad: Vec<usize> = (0..self.positions()).filter(|&k| !notes[k].is_empty()).collect();
        if let Some(&k) = bad.first() {
            w.push(format!(
                "tolerances: the linear result is not to be trusted at {} positions, e.g. {}: {}",
                bad.len(),
                self.at_label(k),
                notes[k].join("; ")
            ));
        }
        w
    }
}

/// The per-component statistics, in column order.
pub(crate) const STATS: [&str; 9] =
    ["nominal", "shift", "wc", "rss", "sigma", "mc_mean", "mc_sigma", "mc_p0.135", "mc_p99.865"];

/// Four significant digits for the terminal.
fn short(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let digits = (3 - libm::log10(v.abs()).floor() as i32).max(0) as usize;
    format!("{v:.digits$}")
}

/// A shard's file: the scene it came from, which share of the chunks, and the counts.
#[cfg(feature = "cli")]
pub(crate) fn shard_json(
    study: &Study,
    scene: (&str, &str, &[String]),
    shard: (u64, u64),
    chunks: &Range<u64>,
) -> Value {
    let tallies: Vec<Value> = study
        .mc
        .tallies
        .iter()
        .map(|t| {
            json!({
                "n": t.n,
                "min": t.min.to_bits(),
                "max": t.max.to_bits(),
                "lo": t.lo.to_bits(),
                "width": t.width.to_bits(),
                "sum": t.sum.digits(),
                "squares": t.squares.digits(),
                "counts": t.counts,
            })
        })
        .collect();
    json!({
        "format": SHARD_FORMAT,
        "scene": { "file": scene.0, "text": scene.1, "sets": scene.2 },
        "name": study.name,
        "samples": study.settings.samples,
        "seed": study.settings.seed,
        "shard": [shard.0, shard.1],
        "chunks": [chunks.start, chunks.end],
        "drawn": study.mc.drawn,
        "failed_samples": study.mc.failed_samples,
        "failed_at": study.mc.failed_at,
        "tallies": tallies,
    })
}

/// The shard files' format tag.
#[cfg(feature = "cli")]
pub(crate) const SHARD_FORMAT: &str = "mechdraw tolerance shard 1";

/// A shard file read back: its scene, share and counts.
#[derive(Debug, Clone)]
#[cfg(feature = "cli")]
pub(crate) struct Shard {
    /// The scene file's name, text and `--set` overrides.
    pub file: String,
    /// Scene text.
    pub text: String,
    /// Overrides.
    pub sets: Vec<String>,
    /// Samples and seed of the whole study.
    pub samples: u64,
    /// Seed.
    pub seed: u64,
    /// K and N.
    pub shard: (u64, u64),
    /// Its counts.
    pub mc: MonteCarlo,
}

/// Reads a shard file's JSON (`what` names it in messages).
#[cfg(feature = "cli")]
pub(crate) fn read_shard(v: &Value, what: &str) -> Result<Shard, String> {
    let bad = |field: &str| format!("{what}: not a mechdraw tolerance shard (field `{field}` missing or malformed)");
    if v.get("format").and_then(Value::as_str) != Some(SHARD_FORMAT) {
        return Err(bad("format"));
    }
    let s = |k: &str| v.pointer(k).and_then(Value::as_str).map(str::to_string).ok_or_else(|| bad(k));
    let u = |k: &str| v.pointer(k).and_then(Value::as_u64).ok_or_else(|| bad(k));
    let sets = v
        .pointer("/scene/sets")
        .and_then(Value::as_array)
        .ok_or_else(|| bad("scene.sets"))?
        .iter()
        .map(|x| x.as_str().map(str::to_string).ok_or_else(|| bad("scene.sets")))
        .collect::<Result<Vec<_>, _>>()?;
    let failed_at = v
        .get("failed_at")
        .and_then(Value::as_array)
        .ok_or_else(|| bad("failed_at"))?
        .iter()
        .map(|x| x.as_u64().ok_or_else(|| bad("failed_at")))
        .collect::<Result<Vec<_>, _>>()?;
    let tallies = v
        .get("tallies")
        .and_then(Value::as_array)
        .ok_or_else(|| bad("tallies"))?
        .iter()
        .map(|t| read_tally(t).ok_or_else(|| bad("tallies")))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Shard {
        file: s("/scene/file")?,
        text: s("/scene/text")?,
        sets,
        samples: u("/samples")?,
        seed: u("/seed")?,
        shard: (u("/shard/0")?, u("/shard/1")?),
        mc: MonteCarlo { drawn: u("/drawn")?, failed_samples: u("/failed_samples")?, failed_at, tallies },
    })
}

#[cfg(feature = "cli")]
fn read_tally(t: &Value) -> Option<crate::solve::tolerance::Tally> {
    use crate::solve::tolerance::{Tally, exact::ExactSum};
    let bits = |k: &str| t.get(k).and_then(Value::as_u64).map(f64::from_bits);
    let digits = |k: &str| -> Option<ExactSum> {
        let list: Option<Vec<(u8, i64)>> = t
            .get(k)?
            .as_array()?
            .iter()
            .map(|p| Some((u8::try_from(p.get(0)?.as_u64()?).ok()?, p.get(1)?.as_i64()?)))
            .collect();
        ExactSum::from_digits(&list?)
    };
    let counts: Option<Vec<u64>> = t.get("counts")?.as_array()?.iter().map(Value::as_u64).collect();
    let counts = counts?;
    if counts.len() < 3 {
        return None;
    }
    let (lo, width) = (bits("lo")?, bits("width")?);
    let mut tally = Tally::new(lo, lo + width * (counts.len() - 2) as f64, counts.len() - 2);
    tally.width = width;
    tally.n = t.get("n")?.as_u64()?;
    tally.min = bits("min")?;
    tally.max = bits("max")?;
    tally.sum = digits("sum")?;
    tally.squares = digits("squares")?;
    tally.counts = counts;
    Some(tally)
}

/// Adds the shards' counts to `study` (whose own Monte Carlo ran no chunk), after checking
/// that they are shards 1..N of this study, each once, with the histogram ranges it uses.
#[cfg(feature = "cli")]
pub(crate) fn merge_shards(study: &mut Study, shards: &[Shard]) -> Result<(), String> {
    let n = shards.first().map_or(0, |s| s.shard.1);
    let mut seen = vec![false; n as usize];
    for s in shards {
        if s.shard.1 != n || s.shard.0 == 0 || s.shard.0 > n {
            return Err(format!("shard {}/{} does not belong to a run in {n} shards", s.shard.0, s.shard.1));
        }
        if std::mem::replace(&mut seen[s.shard.0 as usize - 1], true) {
            return Err(format!("shard {}/{n} is given twice", s.shard.0));
        }
        if s.mc.tallies.len() != study.mc.tallies.len() || s.mc.failed_at.len() != study.mc.failed_at.len() {
            return Err(format!("shard {}/{n} watches another set of positions or components", s.shard.0));
        }
        for (a, b) in s.mc.tallies.iter().zip(&study.mc.tallies) {
            if a.lo.to_bits() != b.lo.to_bits()
                || a.width.to_bits() != b.width.to_bits()
                || a.counts.len() != b.counts.len()
            {
                return Err(format!(
                    "shard {}/{n} counted over other histogram ranges than this build computes: was it made by another version of mechdraw?",
                    s.shard.0
                ));
            }
        }
    }
    let missing: Vec<String> = (1..=n).filter(|k| !seen[*k as usize - 1]).map(|k| format!("{k}/{n}")).collect();
    if !missing.is_empty() {
        return Err(format!("shards missing: {}", missing.join(", ")));
    }
    for s in shards {
        study.mc.merge(&s.mc);
    }
    Ok(())
}

/// The study of `scene` (solved here) with `chunks` of its Monte Carlo; `None` when the
/// scene has no `[tolerances]`.
#[cfg(feature = "cli")]
pub(crate) fn study_of(
    scene: &crate::scene::Scene,
    file: &str,
    chunks: Option<Range<u64>>,
) -> Result<Option<Study>, crate::Error> {
    use crate::scene::Scene;
    match scene {
        Scene::Fourbar(s) => {
            if s.tolerances.is_none() {
                return Ok(None);
            }
            let motion = crate::solve::fourbar::solve_motion(&s.spec).map_err(|e| super::solve_err(file)(e.into()))?;
            Ok(fourbar(s, &motion.positions, chunks))
        }
        Scene::Linkage(s) => linkage(s, chunks).map_err(|e| tolerance_err(file, e)),
        Scene::Triad(s) => {
            if s.tolerances.is_none() {
                return Ok(None);
            }
            let r = super::triad::solve(s).map_err(|e| super::solve_err(file)(e.into()))?;
            Ok(triad(s, &r.triad, &r.modes, chunks))
        }
        _ => Ok(None),
    }
}

/// A linkage study's error as the run reports it (the file named).
pub(crate) fn tolerance_err(file: &str, e: crate::solve::tolerance::linkage::LinkageToleranceError) -> crate::Error {
    use crate::solve::tolerance::linkage::LinkageToleranceError;
    match e {
        LinkageToleranceError::Nominal(le) => super::solve_err(file)(le.into()),
    }
}

/// The samples and seed a scene's study would use, when it has `[tolerances]`.
#[cfg(feature = "cli")]
fn settings_of(scene: &crate::scene::Scene) -> Option<&Settings> {
    use crate::scene::Scene;
    match scene {
        Scene::Fourbar(s) => s.tolerances.as_ref().map(|t| &t.study.settings),
        Scene::Linkage(s) => s.tolerances.as_ref().map(|t| &t.study.settings),
        Scene::Triad(s) => s.tolerances.as_ref().map(|t| &t.study.settings),
        _ => None,
    }
}

/// The study's products without the mechanism: its tables, the summary `{kind, name,
/// tolerances}`, its figures; the picture is its band drawing, which
/// [`to_merged_files`] leaves out (it is also the `-tolerance-band` sheet).
#[cfg(feature = "cli")]
pub(crate) fn products(study: &Study, kind: &str) -> super::Products {
    let mut extras =
        super::products::Extras { summary: json!({ "kind": kind, "name": study.name }), ..Default::default() };
    let warnings = study.add_to(&mut extras);
    super::Products {
        name: study.name.clone(),
        picture: super::products::Picture::Still(crate::draw::Drawing::new(crate::draw::DimStyle {
            text_height: 1.0,
            arrow_size: 1.0,
        })),
        mm_per_unit: super::mm_per_unit(study.units),
        positions: None,
        sheets: extras.sheets,
        pages: Vec::new(),
        diagrams: extras.diagrams,
        tables: extras.tables,
        texts: Vec::new(),
        summary: extras.summary,
        report: extras.report,
        warnings,
        derived: Vec::new(),
        frame_scales: Vec::new(),
    }
}

/// `mechdraw run --shard K/N`: the share K of N of the scene's Monte Carlo, as the partial
/// statistics `<name>-shard-K-of-N.json` in the output directory.
#[cfg(feature = "cli")]
pub fn run_shard(
    loaded: &crate::scene::Loaded,
    shard: (u64, u64),
    sets: &[String],
    out_dir: &std::path::Path,
) -> Result<super::Outcome, crate::Error> {
    let file = loaded.path.display().to_string();
    let (k, n) = shard;
    let option = |message: String| crate::Error::Option { option: "--shard".into(), message };
    if n == 0 || k == 0 || k > n {
        return Err(option(format!("{k}/{n}: give K/N with 1 ≤ K ≤ N, e.g. --shard 2/4")));
    }
    let Some(settings) = settings_of(&loaded.scene) else {
        return Err(option(format!("{file} has no [tolerances] table: there is no Monte Carlo to shard")));
    };
    let chunks = monte_carlo::shard_chunks(settings.samples, k, n);
    let study = study_of(&loaded.scene, &file, Some(chunks.clone()))?
        .ok_or_else(|| option(format!("{file} has no [tolerances] table")))?;
    let name = loaded.path.file_name().map_or_else(|| "scene.toml".into(), |f| f.to_string_lossy().into_owned());
    let v = shard_json(&study, (&name, &loaded.text, sets), shard, &chunks);
    let text =
        serde_json::to_string(&v).map_err(|e| crate::Error::Export { what: "shard".into(), message: e.to_string() })?;
    let rel = format!("{}-shard-{k}-of-{n}.json", study.name);
    let mut out = super::output::Output::new(out_dir)?;
    out.write(&rel, text + "\n")?;
    let written = out.commit()?;
    Ok(super::Outcome {
        summary: json!({ "name": study.name, "shard": [k, n], "chunks": [chunks.start, chunks.end], "drawn": study.mc.drawn }),
        report: format!(
            "shard {k}/{n}: chunks {}..{} of {}, {} samples drawn, {} cannot be assembled\n",
            chunks.start,
            chunks.end,
            chunk_count(settings.samples),
            study.mc.drawn,
            study.mc.failed_samples
        ),
        warnings: Vec::new(),
        written,
    })
}

/// `mechdraw merge SHARD…`: the shards of one study added into the single run's study,
/// written as a run writes its tolerance files (tables, summary, figures).
#[cfg(feature = "cli")]
pub fn merge(paths: &[std::path::PathBuf], opts: &super::RunOptions) -> Result<super::Outcome, crate::Error> {
    let option = |message: String| crate::Error::Option { option: "mechdraw merge".into(), message };
    if paths.is_empty() {
        return Err(option("give the shard files (<name>-shard-K-of-N.json) to merge".into()));
    }
    let mut shards = Vec::new();
    for p in paths {
        let what = p.display().to_string();
        let text = std::fs::read_to_string(p).map_err(|source| crate::Error::Io { path: what.clone(), source })?;
        let v: Value = serde_json::from_str(&text).map_err(|e| option(format!("{what}: not JSON: {e}")))?;
        shards.push(read_shard(&v, &what).map_err(option)?);
    }
    let first = &shards[0];
    for (s, p) in shards.iter().zip(paths) {
        if s.text != first.text || s.sets != first.sets || s.samples != first.samples || s.seed != first.seed {
            return Err(option(format!(
                "{} comes from another study than {} (scene text, --set overrides, samples or seed differ)",
                p.display(),
                paths[0].display()
            )));
        }
    }
    let overrides: Vec<crate::scene::Override> =
        first.sets.iter().map(|s| s.parse()).collect::<Result<_, crate::scene::SceneError>>()?;
    let scene = crate::scene::parse(&first.text, &first.file, &overrides)?;
    let mut study = study_of(&scene, &first.file, Some(0..0))?
        .ok_or_else(|| option("the shards' scene has no [tolerances]".into()))?;
    merge_shards(&mut study, &shards).map_err(option)?;
    let p = products(&study, scene.kind());
    let Some(dir) = &opts.out_dir else {
        return Ok(super::Outcome { summary: p.summary, report: p.report, warnings: p.warnings, written: Vec::new() });
    };
    let files = to_merged_files(&p, opts)?;
    let mut out = super::output::Output::new(dir)?;
    for (rel, bytes) in &files {
        out.write(rel, bytes)?;
    }
    let written = out.commit()?;
    Ok(super::Outcome { summary: p.summary, report: p.report, warnings: p.warnings, written })
}

/// The files of a study's [`products`]: all but the picture (`<name>.dxf`, `.svg`, `.png`).
#[cfg(feature = "cli")]
pub(crate) fn to_merged_files(
    p: &super::Products,
    opts: &super::RunOptions,
) -> Result<Vec<(String, Vec<u8>)>, crate::Error> {
    let wopts = super::bytes::WriteOptions { png: opts.png, no_frames: true, dxf: opts.dxf };
    let picture = [format!("{}.dxf", p.name), format!("{}.svg", p.name), format!("{}.png", p.name)];
    Ok(super::bytes::to_files(p, &wopts)?.into_iter().filter(|(n, _)| !picture.contains(n)).collect())
}
