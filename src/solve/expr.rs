//! Driver laws: expressions of the time `t`, parsed once into a tree and evaluated with
//! their exact first and second time derivatives.
//!
//! Grammar (usual precedence, `^` binds tightest and is right-associative, unary minus
//! binds looser than `^`, so `-t^2 = -(t^2)` and `2^-1 = 0.5`):
//!
//! ```text
//! expr    := term (('+' | '-') term)*
//! term    := unary (('*' | '/') unary)*
//! unary   := ('-' | '+') unary | power
//! power   := primary ('^' unary)?
//! primary := number | 't' | 'pi' | 'e' | 'deg' | function '(' expr ')' | '(' expr ')'
//! ```
//!
//! Numbers: `2`, `0.5`, `.5`, `1e-3`. Constants: `pi`, `e`, `deg` (= π/180, so
//! `360*deg*t` is one turn a second). Functions: `sin cos tan asin acos atan sinh cosh
//! tanh exp ln log (natural) log10 sqrt abs`.
//!
//! Limits: at most [`MAX_CHARS`] characters and [`MAX_DEPTH`] levels of nesting (each
//! parenthesis, function call, sign, exponent and operator of a chain such as `t+t+t` is a
//! level), so that no expression can exhaust the stack of the parser, the evaluator or the
//! tree's drop; a longer or deeper one is refused with a named error.
//!
//! Derivatives are exact: the tree is evaluated on second-order jets (value, d/dt,
//! d²/dt²), the forward-mode analogue of symbolic differentiation, so a driver's velocity
//! and acceleration carry no finite-difference error.
//!
//! ```
//! use mechdraw::solve::expr::Expr;
//! let law = Expr::parse("0.3*sin(4*t) + t^2").unwrap();
//! let j = law.eval(0.5);
//! assert!((j.value - (0.3 * libm::sin(2f64) + 0.25)).abs() < 1e-15);
//! assert!((j.d1 - (1.2 * libm::cos(2f64) + 1.0)).abs() < 1e-15);
//! assert!((j.d2 - (-4.8 * libm::sin(2f64) + 2.0)).abs() < 1e-15);
//! ```

use std::fmt;

/// A value with its first and second derivatives with respect to `t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jet {
    /// f(t).
    pub value: f64,
    /// df/dt.
    pub d1: f64,
    /// d²f/dt².
    pub d2: f64,
}

impl Jet {
    /// (f, f′, f″) when all three are finite, else `None`.
    #[inline]
    pub fn finite(self) -> Option<(f64, f64, f64)> {
        (self.value.is_finite() && self.d1.is_finite() && self.d2.is_finite()).then_some((self.value, self.d1, self.d2))
    }

    fn constant(v: f64) -> Jet {
        Jet { value: v, d1: 0.0, d2: 0.0 }
    }

    /// Chain rule for g(self) with g(v), g'(v), g''(v) given.
    fn chain(self, g: f64, g1: f64, g2: f64) -> Jet {
        Jet { value: g, d1: g1 * self.d1, d2: g2 * self.d1 * self.d1 + g1 * self.d2 }
    }

    fn add(self, o: Jet) -> Jet {
        Jet { value: self.value + o.value, d1: self.d1 + o.d1, d2: self.d2 + o.d2 }
    }

    fn sub(self, o: Jet) -> Jet {
        Jet { value: self.value - o.value, d1: self.d1 - o.d1, d2: self.d2 - o.d2 }
    }

    fn mul(self, o: Jet) -> Jet {
        Jet {
            value: self.value * o.value,
            d1: self.d1 * o.value + self.value * o.d1,
            d2: self.d2 * o.value + 2.0 * self.d1 * o.d1 + self.value * o.d2,
        }
    }

    fn recip(self) -> Jet {
        let v = self.value;
        self.chain(1.0 / v, -1.0 / (v * v), 2.0 / (v * v * v))
    }

    fn neg(self) -> Jet {
        Jet { value: -self.value, d1: -self.d1, d2: -self.d2 }
    }

    /// self^c for a constant exponent c.
    fn powc(self, c: f64) -> Jet {
        let v = self.value;
        if c == 0.0 {
            return Jet::constant(1.0);
        }
        // Integer exponents through powi: exact signs for negative bases.
        let p = |k: f64| -> f64 {
            let e = c - k;
            if e == 0.0 {
                1.0
            } else if e.fract() == 0.0 && e.abs() < 1e9 {
                crate::geom::powi(v, e as i32)
            } else {
                libm::pow(v, e)
            }
        };
        let g1 = c * p(1.0);
        let g2 = if c == 1.0 { 0.0 } else { c * (c - 1.0) * p(2.0) };
        self.chain(p(0.0), g1, g2)
    }
}

/// A one-argument function of the grammar.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Func {
    /// sin
    Sin,
    /// cos
    Cos,
    /// tan
    Tan,
    /// asin
    Asin,
    /// acos
    Acos,
    /// atan
    Atan,
    /// sinh
    Sinh,
    /// cosh
    Cosh,
    /// tanh
    Tanh,
    /// exp
    Exp,
    /// ln (also `log`): natural logarithm
    Ln,
    /// log10
    Log10,
    /// sqrt
    Sqrt,
    /// abs
    Abs,
}

const FUNCS: &[(&str, Func)] = &[
    ("sin", Func::Sin),
    ("cos", Func::Cos),
    ("tan", Func::Tan),
    ("asin", Func::Asin),
    ("acos", Func::Acos),
    ("atan", Func::Atan),
    ("sinh", Func::Sinh),
    ("cosh", Func::Cosh),
    ("tanh", Func::Tanh),
    ("exp", Func::Exp),
    ("ln", Func::Ln),
    ("log", Func::Ln),
    ("log10", Func::Log10),
    ("sqrt", Func::Sqrt),
    ("abs", Func::Abs),
];

impl Func {
    fn apply(self, a: Jet) -> Jet {
        let v = a.value;
        match self {
            Func::Sin => {
                let (s, c) = libm::sincos(v);
                a.chain(s, c, -s)
            }
            Func::Cos => {
                let (s, c) = libm::sincos(v);
                a.chain(c, -s, -c)
            }
            Func::Tan => {
                let t = libm::tan(v);
                let sec2 = 1.0 + t * t;
                a.chain(t, sec2, 2.0 * t * sec2)
            }
            Func::Asin => {
                let w = 1.0 - v * v;
                a.chain(libm::asin(v), 1.0 / w.sqrt(), v / (w * w.sqrt()))
            }
            Func::Acos => {
                let w = 1.0 - v * v;
                a.chain(libm::acos(v), -1.0 / w.sqrt(), -v / (w * w.sqrt()))
            }
            Func::Atan => {
                let w = 1.0 + v * v;
                a.chain(libm::atan(v), 1.0 / w, -2.0 * v / (w * w))
            }
            Func::Sinh => a.chain(libm::sinh(v), libm::cosh(v), libm::sinh(v)),
            Func::Cosh => a.chain(libm::cosh(v), libm::sinh(v), libm::cosh(v)),
            Func::Tanh => {
                let t = libm::tanh(v);
                let s = 1.0 - t * t;
                a.chain(t, s, -2.0 * t * s)
            }
            Func::Exp => {
                let e = libm::exp(v);
                a.chain(e, e, e)
            }
            Func::Ln => a.chain(libm::log(v), 1.0 / v, -1.0 / (v * v)),
            Func::Log10 => {
                let k = std::f64::consts::LN_10;
                a.chain(libm::log10(v), 1.0 / (k * v), -1.0 / (k * v * v))
            }
            Func::Sqrt => {
                let s = v.sqrt();
                a.chain(s, 0.5 / s, -0.25 / (s * v))
            }
            Func::Abs => {
                let sg = if v > 0.0 {
                    1.0
                } else if v < 0.0 {
                    -1.0
                } else {
                    0.0
                };
                a.chain(v.abs(), sg, 0.0)
            }
        }
    }

    fn name(self) -> &'static str {
        FUNCS.iter().find(|(_, f)| *f == self).map_or("?", |(n, _)| n)
    }
}

/// A binary operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^` (right-associative)
    Pow,
}

/// The parsed expression tree.
#[derive(Debug, Clone, PartialEq)]
pub enum Node {
    /// A number or a named constant.
    Const(f64),
    /// The time `t`.
    T,
    /// Unary minus.
    Neg(Box<Node>),
    /// A binary operation.
    Bin(BinOp, Box<Node>, Box<Node>),
    /// A function call.
    Call(Func, Box<Node>),
}

impl Node {
    fn depends_on_t(&self) -> bool {
        match self {
            Node::Const(_) => false,
            Node::T => true,
            Node::Neg(a) | Node::Call(_, a) => a.depends_on_t(),
            Node::Bin(_, a, b) => a.depends_on_t() || b.depends_on_t(),
        }
    }

    fn eval(&self, t: f64) -> Jet {
        match self {
            Node::Const(c) => Jet::constant(*c),
            Node::T => Jet { value: t, d1: 1.0, d2: 0.0 },
            Node::Neg(a) => a.eval(t).neg(),
            Node::Call(f, a) => f.apply(a.eval(t)),
            Node::Bin(op, a, b) => {
                let x = a.eval(t);
                match op {
                    BinOp::Add => x.add(b.eval(t)),
                    BinOp::Sub => x.sub(b.eval(t)),
                    BinOp::Mul => x.mul(b.eval(t)),
                    BinOp::Div => x.mul(b.eval(t).recip()),
                    BinOp::Pow => {
                        if b.depends_on_t() {
                            // a^b = exp(b·ln a), defined for a > 0.
                            Func::Exp.apply(b.eval(t).mul(Func::Ln.apply(x)))
                        } else {
                            x.powc(b.eval(t).value)
                        }
                    }
                }
            }
        }
    }
}

/// `t` itself, or a t-independent factor times it (in the tree's order).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Term {
    /// `t`.
    T,
    /// `k·t` (`k_first`) or `t·k`, k folded into its jet.
    Scaled { k: Jet, k_first: bool },
}

impl Term {
    fn of(node: &Node) -> Option<Term> {
        match node {
            Node::T => Some(Term::T),
            Node::Bin(BinOp::Mul, a, b) => match (a.as_ref(), b.as_ref()) {
                (k, Node::T) if !k.depends_on_t() => Some(Term::Scaled { k: k.eval(0.0), k_first: true }),
                (Node::T, k) if !k.depends_on_t() => Some(Term::Scaled { k: k.eval(0.0), k_first: false }),
                _ => None,
            },
            _ => None,
        }
    }

    /// The value of [`Term::eval`] alone (the same operation on the values).
    #[inline]
    fn value(self, t: f64) -> f64 {
        match self {
            Term::T => t,
            Term::Scaled { k, k_first: true } => k.value * t,
            Term::Scaled { k, k_first: false } => t * k.value,
        }
    }

    /// Its folded constant, if any.
    fn constant(self) -> Option<Jet> {
        match self {
            Term::T => None,
            Term::Scaled { k, .. } => Some(k),
        }
    }

    #[inline]
    fn eval(self, t: f64) -> Jet {
        let tj = Jet { value: t, d1: 1.0, d2: 0.0 };
        match self {
            Term::T => tj,
            Term::Scaled { k, k_first: true } => k.mul(tj),
            Term::Scaled { k, k_first: false } => tj.mul(k),
        }
    }
}

/// The shapes of the usual driver laws (constant, `ω·t`, `φ0 + ω·t`), evaluated without
/// walking the tree: the same jet operations in the same order as [`Node::eval`] (the
/// t-independent subtrees folded once into their jets), so the same bits.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Shape {
    /// No `t` at all.
    Const(Jet),
    /// `t` or `k·t`.
    Term(Term),
    /// `k ± term` (`k_first`) or `term ± k`.
    Shift { k: Jet, term: Term, k_first: bool, sub: bool },
    /// Anything else: the tree.
    Tree,
}

impl Shape {
    fn of(root: &Node) -> Shape {
        if !root.depends_on_t() {
            return Shape::Const(root.eval(0.0));
        }
        if let Some(term) = Term::of(root) {
            return Shape::Term(term);
        }
        if let Node::Bin(op @ (BinOp::Add | BinOp::Sub), a, b) = root {
            let sub = *op == BinOp::Sub;
            if !a.depends_on_t() {
                if let Some(term) = Term::of(b) {
                    return Shape::Shift { k: a.eval(0.0), term, k_first: true, sub };
                }
            } else if !b.depends_on_t()
                && let Some(term) = Term::of(a)
            {
                return Shape::Shift { k: b.eval(0.0), term, k_first: false, sub };
            }
        }
        Shape::Tree
    }

    /// Whether the value alone tells whether the whole jet is finite: a fast shape whose
    /// folded constants are finite with zero derivatives (then f′ and f″ are constants or
    /// k·1, finite for every finite t, and a non-finite t makes the value non-finite too).
    /// The tree, or a constant such as `sqrt(0)` (f′ = 0/0), is not.
    fn value_tells(self) -> bool {
        let plain = |k: Jet| k.value.is_finite() && k.d1 == 0.0 && k.d2 == 0.0;
        match self {
            Shape::Const(k) => plain(k),
            Shape::Term(term) => term.constant().is_none_or(plain),
            Shape::Shift { k, term, .. } => plain(k) && term.constant().is_none_or(plain),
            Shape::Tree => false,
        }
    }
}

/// A parsed driver law f(t).
#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    source: String,
    root: Node,
    shape: Shape,
    /// `shape.value_tells()`, kept.
    value_tells: bool,
}

impl Expr {
    /// Parses `source`; the error says where it went wrong.
    pub fn parse(source: &str) -> Result<Expr, ParseError> {
        let chars = source.chars().count();
        if chars > MAX_CHARS {
            return Err(make_error(
                source,
                MAX_CHARS + 1,
                format!("the expression is longer than {MAX_CHARS} characters ({chars}): write a shorter law"),
            ));
        }
        let tokens = lex(source)?;
        let mut p = Parser { tokens: &tokens, pos: 0, source, nesting: 0 };
        let (root, _) = p.expr()?;
        if let Some(tok) = p.peek() {
            return Err(p.error_at(tok.col, format!("unexpected {} after a complete expression", tok.kind)));
        }
        let shape = Shape::of(&root);
        Ok(Expr { source: source.to_string(), root, shape, value_tells: shape.value_tells() })
    }

    /// The text the expression was parsed from.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// The tree.
    pub fn root(&self) -> &Node {
        &self.root
    }

    /// f(t), f'(t), f''(t). Outside the domain of a function (e.g. `sqrt` of a negative
    /// number) the values are not finite: callers check.
    #[inline(always)]
    pub fn eval(&self, t: f64) -> Jet {
        match self.shape {
            Shape::Const(k) => k,
            Shape::Term(term) => term.eval(t),
            Shape::Shift { k, term, k_first, sub } => {
                let (x, y) = if k_first { (k, term.eval(t)) } else { (term.eval(t), k) };
                if sub { x.sub(y) } else { x.add(y) }
            }
            Shape::Tree => self.root.eval(t),
        }
    }

    /// f(t) alone, bit for bit `eval(t).value`, for a law whose value tells whether f′ and
    /// f″ are finite too (the usual shapes: constant, `ω·t`, `φ0 + ω·t`, with plain
    /// constants); `None` for any other law (evaluate the whole jet with [`Expr::eval`]).
    /// A positions-only step needs no more than this.
    #[inline]
    pub fn value(&self, t: f64) -> Option<f64> {
        if !self.value_tells {
            return None;
        }
        Some(match self.shape {
            Shape::Const(k) => k.value,
            Shape::Term(term) => term.value(t),
            Shape::Shift { k, term, k_first, sub } => {
                let (x, y) = if k_first { (k.value, term.value(t)) } else { (term.value(t), k.value) };
                if sub { x - y } else { x + y }
            }
            Shape::Tree => return None,
        })
    }
}

impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.source)
    }
}

/// Most characters of an expression (a driver law or a load's value).
pub const MAX_CHARS: usize = 10_000;

/// Most levels of nesting of an expression: parentheses, function calls, signs, exponents,
/// and the operators of a chain (`t+t+t` nests two levels: `(t+t)+t`). Bounds the depth of
/// every recursion over the tree (parsing, evaluating, dropping) far below any thread's
/// stack, the browser's included.
pub const MAX_DEPTH: usize = 200;

/// Why an expression does not parse, and where.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{message} at column {column}\n  {text}\n  {caret}")]
pub struct ParseError {
    /// 1-based character column of the problem.
    pub column: usize,
    /// What is wrong and what would be valid.
    pub message: String,
    /// The expression text around the column: at most [`crate::text::QUOTE_CHARS`]
    /// characters, `…` where it was cut.
    pub text: String,
    /// A line with a `^` under the column (in `text`).
    pub caret: String,
}

#[derive(Debug, Clone, PartialEq)]
enum Kind {
    Num(f64),
    Ident(String),
    Op(char),
    LParen,
    RParen,
}

impl fmt::Display for Kind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Kind::Num(v) => write!(f, "number {v}"),
            Kind::Ident(s) => write!(f, "name `{}`", crate::text::excerpt(s)),
            Kind::Op(c) => write!(f, "`{c}`"),
            Kind::LParen => f.write_str("`(`"),
            Kind::RParen => f.write_str("`)`"),
        }
    }
}

#[derive(Debug, Clone)]
struct Token {
    kind: Kind,
    /// 1-based character column.
    col: usize,
}

fn make_error(source: &str, column: usize, message: String) -> ParseError {
    let (text, at) = crate::text::window(source, column);
    ParseError { column, message, text, caret: format!("{}^", " ".repeat(at.saturating_sub(1))) }
}

fn lex(source: &str) -> Result<Vec<Token>, ParseError> {
    let chars: Vec<char> = source.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let col = i + 1;
        if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_digit() || c == '.' {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            // Exponent: e or E followed by an optional sign and digits.
            if i < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
                let mut j = i + 1;
                if j < chars.len() && (chars[j] == '+' || chars[j] == '-') {
                    j += 1;
                }
                if j < chars.len() && chars[j].is_ascii_digit() {
                    while j < chars.len() && chars[j].is_ascii_digit() {
                        j += 1;
                    }
                    i = j;
                }
            }
            let text: String = chars[start..i].iter().collect();
            let v: f64 = text.parse().map_err(|_| {
                make_error(
                    source,
                    col,
                    format!("`{}` is not a number (write e.g. 2, 0.5, 1e-3)", crate::text::excerpt(&text)),
                )
            })?;
            out.push(Token { kind: Kind::Num(v), col });
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            out.push(Token { kind: Kind::Ident(chars[start..i].iter().collect()), col });
        } else if "+-*/^".contains(c) {
            out.push(Token { kind: Kind::Op(c), col });
            i += 1;
        } else if c == '(' {
            out.push(Token { kind: Kind::LParen, col });
            i += 1;
        } else if c == ')' {
            out.push(Token { kind: Kind::RParen, col });
            i += 1;
        } else {
            return Err(make_error(
                source,
                col,
                format!("unexpected character `{c}` (operators are + - * / ^ and parentheses)"),
            ));
        }
    }
    Ok(out)
}

struct Parser<'a> {
    tokens: &'a [Token],
    pos: usize,
    source: &'a str,
    /// Levels of recursion entered (parentheses, calls, signs, exponents).
    nesting: usize,
}

/// A parsed subtree and its depth (nodes on its longest path from the root).
type Sub = (Node, usize);

impl Parser<'_> {
    fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.pos)
    }

    fn end_col(&self) -> usize {
        self.source.chars().count() + 1
    }

    fn error_at(&self, col: usize, message: String) -> ParseError {
        make_error(self.source, col, message)
    }

    fn too_deep(&self, col: usize) -> ParseError {
        self.error_at(
            col,
            format!(
                "the expression is nested deeper than {MAX_DEPTH} levels (parentheses, functions, signs, \
                 exponents, and each operator of a long chain such as t+t+…+t count): write a flatter law"
            ),
        )
    }

    /// Enters one level of recursion at column `col`, refusing to go past [`MAX_DEPTH`].
    fn enter(&mut self, col: usize) -> Result<(), ParseError> {
        self.nesting += 1;
        if self.nesting > MAX_DEPTH { Err(self.too_deep(col)) } else { Ok(()) }
    }

    fn leave(&mut self) {
        self.nesting -= 1;
    }

    /// A node over its children's depths, refused past [`MAX_DEPTH`] (at column `col`).
    fn node(&self, node: Node, depth: usize, col: usize) -> Result<Sub, ParseError> {
        if depth > MAX_DEPTH { Err(self.too_deep(col)) } else { Ok((node, depth)) }
    }

    /// The operator among `ops` at the current token, with its column.
    fn eat_op(&mut self, ops: &str) -> Option<(char, usize)> {
        match self.peek() {
            Some(Token { kind: Kind::Op(c), col }) if ops.contains(*c) => {
                let found = (*c, *col);
                self.pos += 1;
                Some(found)
            }
            _ => None,
        }
    }

    fn expr(&mut self) -> Result<Sub, ParseError> {
        let (mut left, mut depth) = self.term()?;
        while let Some((c, col)) = self.eat_op("+-") {
            let (right, d) = self.term()?;
            let op = if c == '+' { BinOp::Add } else { BinOp::Sub };
            (left, depth) = self.node(Node::Bin(op, Box::new(left), Box::new(right)), 1 + depth.max(d), col)?;
        }
        Ok((left, depth))
    }

    fn term(&mut self) -> Result<Sub, ParseError> {
        let (mut left, mut depth) = self.unary()?;
        while let Some((c, col)) = self.eat_op("*/") {
            let (right, d) = self.unary()?;
            let op = if c == '*' { BinOp::Mul } else { BinOp::Div };
            (left, depth) = self.node(Node::Bin(op, Box::new(left), Box::new(right)), 1 + depth.max(d), col)?;
        }
        Ok((left, depth))
    }

    fn unary(&mut self) -> Result<Sub, ParseError> {
        let Some((c, col)) = self.eat_op("+-") else { return self.power() };
        self.enter(col)?;
        let (inner, d) = self.unary()?;
        self.leave();
        if c == '-' { self.node(Node::Neg(Box::new(inner)), d + 1, col) } else { Ok((inner, d)) }
    }

    fn power(&mut self) -> Result<Sub, ParseError> {
        let (base, d) = self.primary()?;
        if let Some((_, col)) = self.eat_op("^") {
            // Right-associative: the exponent is itself a unary (which contains a power).
            self.enter(col)?;
            let (exponent, e) = self.unary()?;
            self.leave();
            return self.node(Node::Bin(BinOp::Pow, Box::new(base), Box::new(exponent)), 1 + d.max(e), col);
        }
        Ok((base, d))
    }

    fn primary(&mut self) -> Result<Sub, ParseError> {
        let Some(tok) = self.peek().cloned() else {
            return Err(
                self.error_at(self.end_col(), "the expression ends here; expected a number, t, a name or `(`".into())
            );
        };
        self.pos += 1;
        match tok.kind {
            Kind::Num(v) => Ok((Node::Const(v), 1)),
            Kind::LParen => {
                self.enter(tok.col)?;
                let inner = self.expr()?;
                self.leave();
                self.close_paren(tok.col)?;
                Ok(inner)
            }
            Kind::Ident(name) => {
                if let Some((_, f)) = FUNCS.iter().find(|(n, _)| *n == name) {
                    match self.peek() {
                        Some(Token { kind: Kind::LParen, col }) => {
                            let open = *col;
                            self.pos += 1;
                            self.enter(open)?;
                            let (arg, d) = self.expr()?;
                            self.leave();
                            self.close_paren(open)?;
                            self.node(Node::Call(*f, Box::new(arg)), d + 1, tok.col)
                        }
                        _ => Err(self.error_at(
                            tok.col + name.chars().count(),
                            format!("function `{}` needs its argument in parentheses, e.g. {}(t)", f.name(), f.name()),
                        )),
                    }
                } else {
                    match name.as_str() {
                        "t" => Ok((Node::T, 1)),
                        "pi" => Ok((Node::Const(std::f64::consts::PI), 1)),
                        "e" => Ok((Node::Const(std::f64::consts::E), 1)),
                        "deg" => Ok((Node::Const(std::f64::consts::PI / 180.0), 1)),
                        _ => Err(self.error_at(
                            tok.col,
                            format!(
                                "unknown name `{}`: the variable is t, constants are pi, e, deg, functions are {}",
                                crate::text::excerpt(&name),
                                FUNCS.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(" ")
                            ),
                        )),
                    }
                }
            }
            Kind::Op(c) => {
                Err(self.error_at(tok.col, format!("unexpected `{c}`; expected a number, t, a name or `(`")))
            }
            Kind::RParen => Err(self.error_at(tok.col, "unexpected `)`; expected a number, t, a name or `(`".into())),
        }
    }

    fn close_paren(&mut self, open_col: usize) -> Result<(), ParseError> {
        match self.peek() {
            Some(Token { kind: Kind::RParen, .. }) => {
                self.pos += 1;
                Ok(())
            }
            Some(tok) => Err(self.error_at(
                tok.col,
                format!("expected `)` (to close the `(` at column {open_col}), found {}", tok.kind),
            )),
            None => Err(self.error_at(self.end_col(), format!("missing `)` to close the `(` at column {open_col}"))),
        }
    }
}

#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use super::*;

    fn v(s: &str) -> f64 {
        Expr::parse(s).unwrap().eval(0.0).value
    }

    #[test]
    fn the_usual_shapes_give_the_trees_bits() {
        let laws = [
            ("20*t", "term"),
            ("t*20", "term"),
            ("t", "term"),
            ("2*pi*t", "term"),
            ("320*2*pi/60*t", "term"),
            ("pi/2 + 2*pi*t", "shift"),
            ("2*pi*t - pi/3", "shift"),
            ("0.25 - t", "shift"),
            ("-1.5 - t*3", "shift"),
            ("pi/7", "const"),
            ("-0*3", "const"),
            ("t*t", "tree"),
            ("sin(t)", "tree"),
            ("2*t + t", "tree"),
        ];
        let times = [0.0, -0.0, 1.0 / 3.0, -2.75, 1e-300, 7.0e5, 0.1, f64::MIN_POSITIVE];
        for (law, shape) in laws {
            let e = Expr::parse(law).unwrap();
            let got = match e.shape {
                Shape::Const(_) => "const",
                Shape::Term(_) => "term",
                Shape::Shift { .. } => "shift",
                Shape::Tree => "tree",
            };
            assert_eq!(got, shape, "{law}");
            for t in times {
                let (fast, tree) = (e.eval(t), e.root.eval(t));
                for (a, b) in [(fast.value, tree.value), (fast.d1, tree.d1), (fast.d2, tree.d2)] {
                    assert_eq!(a.to_bits(), b.to_bits(), "{law} at t = {t}: {fast:?} against {tree:?}");
                }
                // The value alone: the tree's bits, for every shape but the tree.
                match e.value(t) {
                    Some(v) => assert_eq!(v.to_bits(), tree.value.to_bits(), "{law} at t = {t}"),
                    None => assert_eq!(shape, "tree", "{law}"),
                }
            }
        }
    }

    #[test]
    fn a_value_alone_is_given_only_where_it_tells_whether_the_rates_are_finite() {
        // Over many times, the value is finite exactly when the whole jet is.
        let times = [0.0, 1.0, -3.5, 1e308, -1e308, f64::INFINITY, f64::NEG_INFINITY, f64::NAN, 1e-320];
        for law in ["20*t", "t*0", "0*t", "t", "pi/2 + 2*pi*t", "1e308 + t*1e308", "pi/7", "-0*3", "0.25 - t"] {
            let e = Expr::parse(law).unwrap();
            for t in times {
                let (v, j) = (e.value(t).unwrap(), e.eval(t));
                // The same bits, or both NaN (a NaN's sign and payload are not kept by
                // the optimiser's reordering: a release build gives −NaN for 0.25 − NaN
                // on one path and NaN on the other).
                assert!(
                    v.to_bits() == j.value.to_bits() || (v.is_nan() && j.value.is_nan()),
                    "{law} at {t}: {v} against {j:?}"
                );
                let all = j.value.is_finite() && j.d1.is_finite() && j.d2.is_finite();
                assert_eq!(v.is_finite(), all, "{law} at {t}: {j:?}");
            }
        }
        // A constant with a non-finite derivative, and the tree: the whole jet is needed.
        for law in ["sqrt(0)", "sqrt(0)*t", "1 + sqrt(0)*t", "sqrt(t)", "t*t", "1/0"] {
            assert_eq!(Expr::parse(law).unwrap().value(1.0), None, "{law}");
        }
    }

    #[test]
    fn precedence_and_associativity() {
        assert_eq!(v("1 + 2 * 3"), 7.0);
        assert_eq!(v("(1 + 2) * 3"), 9.0);
        assert_eq!(v("8 / 4 / 2"), 1.0); // left-assoc
        assert_eq!(v("10 - 4 - 3"), 3.0);
        assert_eq!(v("2 ^ 3 ^ 2"), 512.0); // right-assoc: 2^9
        assert_eq!(v("-2 ^ 2"), -4.0); // unary minus looser than ^
        assert_eq!(v("2 ^ -1"), 0.5);
        assert_eq!(v("--3"), 3.0);
        assert_eq!(v("2 * -3"), -6.0);
        assert_eq!(v("1.5e2 + .5"), 150.5);
        assert_eq!(v("2E-1"), 0.2);
        assert!((v("pi") - std::f64::consts::PI).abs() < 1e-16);
        assert!((v("180*deg") - std::f64::consts::PI).abs() < 1e-15);
        assert!((v("ln(e)") - 1.0).abs() < 1e-16);
        assert!((v("log10(1000)") - 3.0).abs() < 1e-15);
        assert_eq!(v("sqrt(16) + abs(-2)"), 6.0);
        assert!((v("cos(pi)") + 1.0).abs() < 1e-16);
    }

    /// Each case: expression, hand-derived f, f', f''.
    type Case = (&'static str, fn(f64) -> [f64; 3]);

    #[test]
    fn derivatives_match_hand_derivatives_and_finite_differences() {
        let cases: &[Case] = &[
            ("0.3*sin(4*t) + t^2", |t| {
                [0.3 * (4.0 * t).sin() + t * t, 1.2 * (4.0 * t).cos() + 2.0 * t, -4.8 * (4.0 * t).sin() + 2.0]
            }),
            ("2*pi*t", |_t| [2.0 * std::f64::consts::PI * _t, 2.0 * std::f64::consts::PI, 0.0]),
            ("exp(-t)*cos(3*t)", |t| {
                let (e, c, s) = ((-t).exp(), (3.0 * t).cos(), (3.0 * t).sin());
                [e * c, e * (-c - 3.0 * s), e * (c + 6.0 * s - 9.0 * c)]
            }),
            ("1/(1+t^2)", |t| {
                let w = 1.0 + t * t;
                [1.0 / w, -2.0 * t / (w * w), (6.0 * t * t - 2.0) / (w * w * w)]
            }),
            ("t^t", |t| {
                let f = t.powf(t);
                let l = t.ln() + 1.0;
                [f, f * l, f * (l * l + 1.0 / t)]
            }),
            ("sqrt(1+t)", |t| [(1.0 + t).sqrt(), 0.5 / (1.0 + t).sqrt(), -0.25 / (1.0 + t).powf(1.5)]),
            ("atan(t) - asin(t/2) + acos(t/3)", |t| {
                let a = [t.atan(), 1.0 / (1.0 + t * t), -2.0 * t / (1.0 + t * t).powi(2)];
                let w = 1.0 - t * t / 4.0;
                let b = [(t / 2.0).asin(), 0.5 / w.sqrt(), 0.125 * t / w.powf(1.5)];
                let u = 1.0 - t * t / 9.0;
                let c = [(t / 3.0).acos(), -(1.0 / 3.0) / u.sqrt(), -(t / 27.0) / u.powf(1.5)];
                [a[0] - b[0] + c[0], a[1] - b[1] + c[1], a[2] - b[2] + c[2]]
            }),
            ("tan(t) + tanh(t) + sinh(t)*cosh(t)", |t| {
                let sec2 = 1.0 / t.cos().powi(2);
                let sech2 = 1.0 - t.tanh().powi(2);
                [
                    t.tan() + t.tanh() + t.sinh() * t.cosh(),
                    sec2 + sech2 + (2.0 * t).cosh(),
                    2.0 * t.tan() * sec2 - 2.0 * t.tanh() * sech2 + 2.0 * (2.0 * t).sinh(),
                ]
            }),
            ("(t-2)^3", |t| [(t - 2.0).powi(3), 3.0 * (t - 2.0).powi(2), 6.0 * (t - 2.0)]),
            ("ln(t) + log10(t)", |t| {
                let k = std::f64::consts::LN_10;
                [t.ln() + t.log10(), 1.0 / t + 1.0 / (k * t), -1.0 / (t * t) - 1.0 / (k * t * t)]
            }),
        ];
        for (src, hand) in cases {
            let e = Expr::parse(src).unwrap();
            for &t in &[0.3, 0.7, 1.1] {
                let j = e.eval(t);
                let h = hand(t);
                for (k, (got, want)) in [j.value, j.d1, j.d2].iter().zip(h).enumerate() {
                    assert!(
                        (got - want).abs() <= 1e-12 * want.abs().max(1.0),
                        "{src} at t={t}: d{k} = {got}, hand {want}"
                    );
                }
                // Central finite differences (independent of the hand derivatives).
                let dt = 1e-4;
                let (fm, fp) = (e.eval(t - dt), e.eval(t + dt));
                let fd1 = (fp.value - fm.value) / (2.0 * dt);
                let fd2 = (fp.value - 2.0 * j.value + fm.value) / (dt * dt);
                assert!((fd1 - j.d1).abs() <= 1e-6 * j.d1.abs().max(1.0), "{src}: fd d1 {fd1} vs {}", j.d1);
                assert!((fd2 - j.d2).abs() <= 1e-4 * j.d2.abs().max(1.0), "{src}: fd d2 {fd2} vs {}", j.d2);
                let fdd = (fp.d1 - fm.d1) / (2.0 * dt);
                assert!((fdd - j.d2).abs() <= 1e-6 * j.d2.abs().max(1.0), "{src}: fd of d1 {fdd} vs {}", j.d2);
            }
        }
    }

    #[test]
    fn errors_point_at_the_column() {
        let e = Expr::parse("0.3*sin(4*t +").unwrap_err();
        assert_eq!(e.column, 14, "{e}");
        assert!(e.to_string().contains("0.3*sin(4*t +\n               ^"), "{e}");
        let e = Expr::parse("2*x + 1").unwrap_err();
        assert_eq!(e.column, 3);
        assert!(e.message.contains("unknown name `x`"));
        let e = Expr::parse("sin t").unwrap_err();
        assert_eq!(e.column, 4);
        assert!(e.message.contains("parentheses"));
        let e = Expr::parse("(t + 1").unwrap_err();
        assert_eq!(e.column, 7);
        assert!(e.message.contains("missing `)`"), "{e}");
        let e = Expr::parse("t $ 2").unwrap_err();
        assert_eq!(e.column, 3);
        let e = Expr::parse("t 2").unwrap_err();
        assert_eq!(e.column, 3);
        assert!(e.message.contains("after a complete expression"));
        let e = Expr::parse("1.2.3").unwrap_err();
        assert_eq!(e.column, 1);
        let e = Expr::parse("").unwrap_err();
        assert_eq!(e.column, 1);
        let e = Expr::parse("3 * )").unwrap_err();
        assert_eq!(e.column, 5);
    }

    /// Issue 28 item 2: these crashed the process (stack overflow, SIGABRT) before the limits.
    #[test]
    fn deep_or_long_expressions_are_refused_by_name_and_quoted_short() {
        let nested = |n: usize| format!("{}t{}", "(".repeat(n), ")".repeat(n));
        let deep = [
            nested(4_999),
            "(".repeat(9_999),
            format!("{}t", "-".repeat(9_000)),
            format!("{}t", "+-".repeat(4_000)),
            format!("t{}", "^t".repeat(4_000)),
            format!("t{}", "+t".repeat(4_000)),
            format!("{}t{}", "sin(".repeat(1_900), ")".repeat(1_900)),
        ];
        for text in &deep {
            let e = Expr::parse(text).unwrap_err();
            assert!(e.message.contains(&format!("nested deeper than {MAX_DEPTH} levels")), "{}", e.message);
            assert!(e.text.chars().count() <= crate::text::QUOTE_CHARS, "{}", e.text);
        }
        for text in [format!("{}t", "-".repeat(100_000)), format!("t{}", "+t".repeat(50_000)), "x".repeat(1 << 20)] {
            let e = Expr::parse(&text).unwrap_err();
            assert!(e.message.contains(&format!("longer than {MAX_CHARS} characters")), "{}", e.message);
            assert!(e.to_string().chars().count() < 400, "{e}");
        }
        // A megabyte-long unknown name within the limit's length is quoted short too.
        let e = Expr::parse(&"y".repeat(MAX_CHARS)).unwrap_err();
        assert!(e.to_string().chars().count() < 400 && e.message.contains("unknown name"), "{e}");
        // Just inside the limits: parsed, and evaluated as written.
        assert_eq!(Expr::parse(&nested(MAX_DEPTH - 1)).unwrap().eval(2.0).value, 2.0);
        let sum = format!("t{}", "+t".repeat(MAX_DEPTH - 1));
        assert_eq!(Expr::parse(&sum).unwrap().eval(0.5).value, 0.5 * MAX_DEPTH as f64);
        assert!(Expr::parse(&format!("t{}", "+t".repeat(MAX_DEPTH))).is_err());
        let signs = format!("{}t", "-".repeat(MAX_DEPTH - 1));
        assert_eq!(Expr::parse(&signs).unwrap().eval(1.0).value, -1.0);
    }

    #[test]
    fn domain_errors_give_non_finite_values() {
        assert!(!Expr::parse("sqrt(t - 1)").unwrap().eval(0.0).value.is_finite());
        assert!(!Expr::parse("ln(t)").unwrap().eval(0.0).value.is_finite());
    }
}
