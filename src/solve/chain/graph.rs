//! The chain as a graph: coordinates, redundancy, under-dimensioning, dimensional functions.
//!
//! Features are nodes, independent dimensions are edges `from → to` with the signed value
//! x_to − x_from. A spanning forest is grown over the dimensions in the order they are
//! written (union–find): a dimension whose ends are already tied is redundant, and closes
//! the loop made of itself and the tree path between its ends. The number of redundant
//! dimensions is edges − nodes + components. Coordinates come from the tree, with the first
//! feature (the zero point) at 0.
//!
//! The matrix form needs one step first (the seed's check, section 3): every base is
//! replaced by the coordinate it stands for ("all bases zero"), and end points that
//! coincide are one feature. p coinciding end points are p − 1 redundant dimensions.

use super::ChainError;
use super::model::{Chain, Dependent, Dimension, Form};

/// Two matrix-form end points closer than this (model units) are one feature: below the
/// 0.0001 mm by which the seed perturbs equal nominal values.
pub const COINCIDE_TOL: f64 = 1e-6;
/// A loop closes when the sum of its signed nominal values is within this fraction of the
/// sum of their magnitudes (rounding of decimal inputs); beyond it the loop contradicts itself.
pub const LOOP_CLOSURE_REL_TOL: f64 = 1e-9;

/// A feature of the part (a surface, an axis): a node of the graph.
#[derive(Debug, Clone, PartialEq)]
pub struct Feature {
    /// Name: as written (named form), or the value of the first dimension ending there
    /// (matrix form; `0` for the zero point).
    pub name: String,
    /// Other names of the same feature (matrix form: further dimensions ending there).
    pub aliases: Vec<String>,
    /// Coordinate on the axis (model units), from the zero point; for a group not tied to
    /// the zero point, from the group's first feature.
    pub x: f64,
    /// Whether the feature is tied to the zero point by dimensions.
    pub tied: bool,
}

/// A redundant dimension: one more than the chain needs.
#[derive(Debug, Clone, PartialEq)]
pub struct Redundant {
    /// Index of the dimension found redundant (the later one in the order written).
    pub dim: usize,
    /// The loop it closes: the other dimensions with their signs, such that
    /// dim = Σ sign·w over the loop when the chain is consistent.
    pub path: Vec<Term>,
    /// Σ sign·w over `path` − the dimension's own nominal value (0 for a plain repeat).
    pub residual: f64,
    /// Whether the loop's nominal values contradict each other (|residual| beyond
    /// [`LOOP_CLOSURE_REL_TOL`]).
    pub contradiction: bool,
    /// Index of the dimension suggested as a reference dimension "(ref)": the loosest
    /// tolerance in the loop (the redundant one itself on a tie).
    pub suggest_ref: usize,
}

/// One term of a dimensional function: `coef · w_dim` with coef = ±1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Term {
    /// Index of the independent dimension.
    pub dim: usize,
    /// +1 or −1.
    pub coef: f64,
}

/// A dimensional function Z = Σ coef·w (the seed's "równanie łańcucha").
#[derive(Debug, Clone, PartialEq)]
pub struct Function {
    /// Terms in the order of the dimensions.
    pub terms: Vec<Term>,
    /// Nominal value Σ coef·w.
    pub nominal: f64,
}

impl Function {
    /// The equation with names and values, e.g. `Z1 = w1 - w2 + w3 = (-38) - 25 + 80 = 17`.
    pub fn equation(&self, z: &str, dims: &[Dimension]) -> String {
        if self.terms.is_empty() {
            return format!("{z} = 0");
        }
        let mut names = String::new();
        let mut values = String::new();
        for (k, t) in self.terms.iter().enumerate() {
            let minus = t.coef < 0.0;
            let d = &dims[t.dim];
            let v = fmt_value(d.nominal);
            let v = if d.nominal < 0.0 { format!("({v})") } else { v };
            match (k, minus) {
                (0, false) => {
                    names.push_str(&d.name);
                    values.push_str(&v);
                }
                (0, true) => {
                    names.push_str(&format!("-{}", d.name));
                    values.push_str(&format!("-{v}"));
                }
                (_, false) => {
                    names.push_str(&format!(" + {}", d.name));
                    values.push_str(&format!(" + {v}"));
                }
                (_, true) => {
                    names.push_str(&format!(" - {}", d.name));
                    values.push_str(&format!(" - {v}"));
                }
            }
        }
        format!("{z} = {names} = {values} = {}", fmt_value(self.nominal))
    }

    /// The function with names only, e.g. `w1 - w2 + w3`.
    pub fn names(&self, dims: &[Dimension]) -> String {
        let mut s = String::new();
        for (k, t) in self.terms.iter().enumerate() {
            let n = &dims[t.dim].name;
            match (k, t.coef < 0.0) {
                (0, false) => s.push_str(n),
                (0, true) => s.push_str(&format!("-{n}")),
                (_, false) => s.push_str(&format!(" + {n}")),
                (_, true) => s.push_str(&format!(" - {n}")),
            }
        }
        if s.is_empty() { "0".into() } else { s }
    }
}

/// A value as a person writes it: at most 6 decimals, trailing zeros trimmed.
pub fn fmt_value(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// The analysed chain.
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    /// Features (merged nodes), the zero point first.
    pub features: Vec<Feature>,
    /// Node of each input feature (matrix form: coinciding end points share one).
    pub node_of: Vec<usize>,
    /// Whether each dimension is in the spanning tree (independent, not redundant).
    pub in_tree: Vec<bool>,
    /// Redundant dimensions, in the order written.
    pub redundant: Vec<Redundant>,
    /// The seed's check (matrix form): groups of dimensions whose end points coincide when
    /// every base is made zero (p of them = p − 1 redundant). Empty for the named form.
    pub coincident: Vec<Vec<usize>>,
    /// Groups of features not tied to the zero point (under-dimensioning), as node indices.
    pub untied: Vec<Vec<usize>>,
    /// Number of connected groups of features (1 when the chain is fully tied).
    pub components: usize,
    parent: Vec<Option<(usize, usize)>>,
    depth: Vec<usize>,
    component: Vec<usize>,
}

struct UnionFind(Vec<usize>);

impl UnionFind {
    fn find(&mut self, mut a: usize) -> usize {
        while self.0[a] != a {
            self.0[a] = self.0[self.0[a]];
            a = self.0[a];
        }
        a
    }
    /// Joins the sets of `a` and `b`; false when they were one set already.
    fn union(&mut self, a: usize, b: usize) -> bool {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return false;
        }
        let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
        self.0[hi] = lo;
        true
    }
}

/// Matrix form: coordinates of the input features with every base made zero (the seed's
/// transformation); `None` for end points whose bases never reach the zero point.
fn matrix_coordinates(n_features: usize, dims: &[Dimension]) -> Vec<Option<f64>> {
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); n_features];
    for (i, d) in dims.iter().enumerate() {
        children[d.from].push(i);
    }
    let mut x = vec![None; n_features];
    x[0] = Some(0.0);
    let mut stack = vec![0usize];
    while let Some(f) = stack.pop() {
        let xf = x[f].unwrap_or(0.0);
        for &i in &children[f] {
            let t = dims[i].to;
            if x[t].is_none() {
                x[t] = Some(xf + dims[i].nominal);
                stack.push(t);
            }
        }
    }
    x
}

/// Builds the graph of `chain` and finds coordinates, redundant dimensions and untied groups.
pub fn analyse(chain: &Chain) -> Analysis {
    let dims = &chain.dimensions;
    let nf = chain.features.len();
    // Merge coinciding end points (matrix form).
    let mut node_of: Vec<usize> = (0..nf).collect();
    let mut coincident = Vec::new();
    let mut node_names: Vec<(String, Vec<String>)>;
    if chain.form == Form::Matrix {
        let x = matrix_coordinates(nf, dims);
        let mut order: Vec<usize> = (0..nf).filter(|&f| x[f].is_some()).collect();
        order.sort_by(|&a, &b| x[a].unwrap_or(0.0).total_cmp(&x[b].unwrap_or(0.0)).then(a.cmp(&b)));
        let mut rep: Vec<usize> = (0..nf).collect();
        let mut k = 0;
        while k < order.len() {
            let mut j = k + 1;
            while j < order.len() && x[order[j]].unwrap_or(0.0) - x[order[j - 1]].unwrap_or(0.0) < COINCIDE_TOL {
                j += 1;
            }
            let group = &order[k..j];
            let first = *group.iter().min().unwrap_or(&order[k]);
            for &f in group {
                rep[f] = first;
            }
            if group.len() > 1 {
                // Dimensions ending there (feature f ≥ 1 is the end of W[f − 1]).
                let mut g: Vec<usize> = group.iter().filter(|&&f| f > 0).map(|&f| f - 1).collect();
                g.sort_unstable();
                coincident.push(g);
            }
            k = j;
        }
        coincident.sort();
        // Number the nodes by the lowest input feature in each.
        let mut id = vec![usize::MAX; nf];
        let mut next = 0;
        node_names = Vec::new();
        for f in 0..nf {
            let r = rep[f];
            if id[r] == usize::MAX {
                id[r] = next;
                next += 1;
                node_names.push((chain.features[f].clone(), Vec::new()));
            } else if !node_names[id[r]].1.contains(&chain.features[f]) && node_names[id[r]].0 != chain.features[f] {
                node_names[id[r]].1.push(chain.features[f].clone());
            }
            node_of[f] = id[r];
        }
    } else {
        node_names = chain.features.iter().map(|n| (n.clone(), Vec::new())).collect();
    }
    let nn = node_names.len();

    // Spanning forest in the order written.
    let mut uf = UnionFind((0..nn).collect());
    let mut in_tree = vec![false; dims.len()];
    let mut adj: Vec<Vec<usize>> = vec![Vec::new(); nn];
    for (i, d) in dims.iter().enumerate() {
        let (a, b) = (node_of[d.from], node_of[d.to]);
        if a != b && uf.union(a, b) {
            in_tree[i] = true;
            adj[a].push(i);
            adj[b].push(i);
        }
    }

    // Coordinates, parents and depths by a walk from each group's first node.
    let mut x = vec![0.0; nn];
    let mut parent: Vec<Option<(usize, usize)>> = vec![None; nn];
    let mut depth = vec![0usize; nn];
    let mut component = vec![usize::MAX; nn];
    let mut components = 0;
    for root in 0..nn {
        if component[root] != usize::MAX {
            continue;
        }
        component[root] = components;
        let mut stack = vec![root];
        while let Some(u) = stack.pop() {
            for &e in &adj[u] {
                let d = &dims[e];
                let (a, b) = (node_of[d.from], node_of[d.to]);
                let (v, xv) = if a == u { (b, x[u] + d.nominal) } else { (a, x[u] - d.nominal) };
                if component[v] == usize::MAX {
                    component[v] = components;
                    x[v] = xv;
                    parent[v] = Some((u, e));
                    depth[v] = depth[u] + 1;
                    stack.push(v);
                }
            }
        }
        components += 1;
    }
    let zero_comp = component[0];
    let features: Vec<Feature> = node_names
        .into_iter()
        .enumerate()
        .map(|(i, (name, aliases))| Feature { name, aliases, x: x[i], tied: component[i] == zero_comp })
        .collect();
    let mut untied: Vec<Vec<usize>> = Vec::new();
    for c in 0..components {
        if c == zero_comp {
            continue;
        }
        untied.push((0..nn).filter(|&i| component[i] == c).collect());
    }

    let mut analysis = Analysis {
        features,
        node_of,
        in_tree,
        redundant: Vec::new(),
        coincident,
        untied,
        components,
        parent,
        depth,
        component,
    };
    for (i, d) in dims.iter().enumerate() {
        if analysis.in_tree[i] {
            continue;
        }
        let (a, b) = (analysis.node_of[d.from], analysis.node_of[d.to]);
        let path = analysis.tree_path(a, b, dims);
        let sum: f64 = path.iter().map(|t| t.coef * dims[t.dim].nominal).sum();
        let scale: f64 = path.iter().map(|t| dims[t.dim].nominal.abs()).sum::<f64>() + d.nominal.abs();
        let residual = sum - d.nominal;
        let contradiction = residual.abs() > LOOP_CLOSURE_REL_TOL * scale;
        let mut suggest_ref = i;
        for t in &path {
            if dims[t.dim].half() > dims[suggest_ref].half() {
                suggest_ref = t.dim;
            }
        }
        analysis.redundant.push(Redundant { dim: i, path, residual, contradiction, suggest_ref });
    }
    analysis
}

impl Analysis {
    /// Terms of x_b − x_a along the spanning tree (a and b in one group).
    fn tree_path(&self, a: usize, b: usize, dims: &[Dimension]) -> Vec<Term> {
        let mut terms = Vec::new();
        let (mut u, mut v) = (a, b);
        // Down-edge sign: +1 when the dimension points from parent to child.
        let sign = |child: usize, e: usize| if self.node_of[dims[e].to] == child { 1.0 } else { -1.0 };
        while self.depth[u] > self.depth[v] {
            let Some((p, e)) = self.parent[u] else { break };
            terms.push(Term { dim: e, coef: -sign(u, e) });
            u = p;
        }
        while self.depth[v] > self.depth[u] {
            let Some((p, e)) = self.parent[v] else { break };
            terms.push(Term { dim: e, coef: sign(v, e) });
            v = p;
        }
        while u != v {
            let (Some((pu, eu)), Some((pv, ev))) = (self.parent[u], self.parent[v]) else { break };
            terms.push(Term { dim: eu, coef: -sign(u, eu) });
            terms.push(Term { dim: ev, coef: sign(v, ev) });
            u = pu;
            v = pv;
        }
        terms.sort_by_key(|t| t.dim);
        terms
    }

    /// Number of redundant dimensions: edges − nodes + components.
    pub fn redundant_count(&self, n_dims: usize) -> usize {
        n_dims + self.components - self.features.len()
    }

    /// The dimensional function of a dependent dimension Z = x_right − x_left of `chain`
    /// (the chain this analysis was made of).
    pub fn function(&self, chain: &Chain, z: &Dependent) -> Result<Function, ChainError> {
        let (l, r) = (self.node_of[z.left], self.node_of[z.right]);
        if self.component[l] != self.component[r] {
            return Err(ChainError::NotDetermined {
                z: z.name.clone(),
                why: format!(
                    "{} = {}: {} is not tied to {} by dimensions (under-dimensioned; groups of features not \
                     tied to the zero point: {})",
                    z.name,
                    z.label,
                    self.features[r].name,
                    self.features[l].name,
                    self.untied_text()
                ),
            });
        }
        let terms = self.tree_path(l, r, &chain.dimensions);
        let nominal = terms.iter().map(|t| t.coef * chain.dimensions[t.dim].nominal).sum();
        Ok(Function { terms, nominal })
    }

    /// The untied groups as text: `{C, D}; {E}`, or `none`.
    pub fn untied_text(&self) -> String {
        if self.untied.is_empty() {
            return "none".into();
        }
        self.untied
            .iter()
            .map(|g| {
                format!("{{{}}}", g.iter().map(|&i| self.features[i].name.as_str()).collect::<Vec<_>>().join(", "))
            })
            .collect::<Vec<_>>()
            .join("; ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dim(name: &str, from: usize, to: usize, nominal: f64) -> Dimension {
        Dimension { name: name.into(), from, to, nominal, upper: 0.1, lower: -0.1 }
    }

    fn named(features: &[&str], dims: Vec<Dimension>) -> Chain {
        Chain {
            form: Form::Named,
            features: features.iter().map(|s| s.to_string()).collect(),
            dimensions: dims,
            dependent: vec![],
        }
    }

    #[test]
    fn a_square_loop_is_one_redundant_dimension_and_its_path_sums_to_it() {
        // A —10→ B —20→ C, and A —30→ C closes the loop: 30 = w1 + w2.
        let s = named(&["A", "B", "C"], vec![dim("w1", 0, 1, 10.0), dim("w2", 1, 2, 20.0), dim("w3", 0, 2, 30.0)]);
        let a = analyse(&s);
        assert_eq!(a.redundant.len(), 1);
        assert_eq!(a.redundant_count(3), 1);
        let r = &a.redundant[0];
        assert_eq!(r.dim, 2);
        assert_eq!(r.path, vec![Term { dim: 0, coef: 1.0 }, Term { dim: 1, coef: 1.0 }]);
        assert!(!r.contradiction);
        // 29 instead of 30 contradicts the others by −1.
        let s = named(&["A", "B", "C"], vec![dim("w1", 0, 1, 10.0), dim("w2", 1, 2, 20.0), dim("w3", 0, 2, 29.0)]);
        let r = &analyse(&s).redundant[0];
        assert!(r.contradiction);
        assert!((r.residual - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_reversed_dimension_enters_the_function_with_a_minus_sign() {
        // B is 10 right of A; C is 4 left of B written as C → B = +4 (from C to B).
        let s = named(&["A", "B", "C"], vec![dim("a", 0, 1, 10.0), dim("c", 2, 1, 4.0)]);
        let a = analyse(&s);
        assert_eq!(a.features[2].x, 6.0);
        let z = Dependent { name: "Z".into(), left: 0, right: 2, label: String::new(), spec: None };
        let f = a.function(&s, &z).unwrap();
        assert_eq!(f.terms, vec![Term { dim: 0, coef: 1.0 }, Term { dim: 1, coef: -1.0 }]);
        assert_eq!(f.nominal, 6.0);
        assert_eq!(f.equation("Z", &s.dimensions), "Z = a - c = 10 - 4 = 6");
    }

    #[test]
    fn matrix_end_points_at_the_zero_point_or_at_each_other_are_the_seeds_over_dimensioning() {
        // B = [0, -38, 0, 25], W = [-38, 38, 25, -25]: w2 = 38 from the end of -38 returns to
        // 0 (coincides with the zero point); w4 = -25 from the end of 25 returns to 0 as well.
        // Three points at 0 (zero point, ends of w2 and w4): p = 3, p − 1 = 2 redundant.
        let s = Chain {
            form: Form::Matrix,
            features: ["0", "-38", "38", "25", "-25"].iter().map(|s| s.to_string()).collect(),
            dimensions: vec![
                dim("w1", 0, 1, -38.0),
                dim("w2", 1, 2, 38.0),
                dim("w3", 0, 3, 25.0),
                dim("w4", 3, 4, -25.0),
            ],
            dependent: vec![],
        };
        let a = analyse(&s);
        assert_eq!(a.coincident, vec![vec![1, 3]]);
        assert_eq!(a.features.len(), 3);
        assert_eq!(a.redundant_count(4), 2);
        assert_eq!(a.redundant.iter().map(|r| r.dim).collect::<Vec<_>>(), vec![1, 3]);
        assert!(a.redundant.iter().all(|r| !r.contradiction));
    }
}
