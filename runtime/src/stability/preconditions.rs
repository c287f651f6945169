//! Documented preconditions, read from the comment above a function or shader, so that the sweep
//! respects them without a list kept in Rust.
//!
//! In the `//` comment block directly above a definition, a line
//!
//! ```text
//! // sweep: NAME in [LO, HI]       the parameter's values are clamped into [LO, HI]
//! // sweep: NAME in {V, V, ..}     the parameter takes only these values (the first is nominal)
//! // sweep: NAME length N          an unsized array parameter gets N elements
//! ```
//!
//! states one (several may share a line, separated by `;`). For a vector or colour the range and
//! the values apply to each component. Anything else after `sweep:` is an error the sweep reports,
//! so a misspelt precondition is not silently ignored.

/// One parameter's precondition.
#[derive(Clone, Debug, PartialEq)]
pub struct Precondition {
    /// The parameter.
    pub param: String,
    /// What it says.
    pub rule: Rule,
}

/// What a precondition says.
#[derive(Clone, Debug, PartialEq)]
pub enum Rule {
    /// Values are clamped into `[lo, hi]`.
    Range(f64, f64),
    /// Only these values.
    Values(Vec<f64>),
    /// An unsized array's length.
    Length(usize),
    /// A line that does not parse, kept to be reported.
    Invalid(String),
}

/// Everything the preconditions say about one parameter.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Constraint {
    /// The range its values are clamped into.
    pub range: Option<(f64, f64)>,
    /// The only values it takes.
    pub values: Option<Vec<f64>>,
    /// The length of an unsized array.
    pub length: Option<usize>,
}

impl Constraint {
    /// `x` moved into the constraint: clamped into the range, or the nearest allowed value.
    pub fn apply(&self, x: f64) -> f64 {
        let x = match &self.values {
            Some(values) if !values.is_empty() => {
                // Clamped into the values' span first: far outside it every distance rounds alike.
                let (lo, hi) = values.iter().fold((f64::MAX, f64::MIN), |(l, h), v| (l.min(*v), h.max(*v)));
                let x = x.clamp(lo, hi);
                *values.iter().min_by(|a, b| (*a - x).abs().total_cmp(&(*b - x).abs())).unwrap_or(&x)
            }
            _ => x,
        };
        match self.range {
            Some((lo, hi)) => x.clamp(lo, hi),
            None => x,
        }
    }
}

/// The preconditions stated in the comment lines directly above byte `start` of `text`.
pub fn before(text: &str, start: usize) -> Vec<Precondition> {
    let mut out = Vec::new();
    for line in patina_compiler::source::comment_above(text, start) {
        if let Some(rest) = line.trim().strip_prefix("sweep:") {
            out.extend(rest.split(';').map(str::trim).filter(|c| !c.is_empty()).map(parse));
        }
    }
    out
}

/// One clause: `NAME in [LO, HI]`, `NAME in {V, ..}` or `NAME length N`.
fn parse(clause: &str) -> Precondition {
    let invalid = || Precondition { param: String::new(), rule: Rule::Invalid(clause.to_string()) };
    let mut words = clause.splitn(3, char::is_whitespace);
    let (Some(param), Some(verb), Some(rest)) = (words.next(), words.next(), words.next()) else {
        return invalid();
    };
    // A clause may end with an explanation in parentheses.
    let rest = rest.trim();
    let end = match rest.chars().next() {
        Some('[') => rest.find(']').map(|i| i + 1),
        Some('{') => rest.find('}').map(|i| i + 1),
        _ => Some(rest.find(char::is_whitespace).unwrap_or(rest.len())),
    };
    let Some(end) = end else { return invalid() };
    let (rest, tail) = rest.split_at(end);
    let tail = tail.trim();
    let explained = tail.is_empty() || (tail.starts_with('(') && tail.ends_with(')'));
    if !explained {
        return invalid();
    }
    let numbers = |inner: &str| -> Option<Vec<f64>> {
        inner.split(',').map(|v| v.trim().parse::<f64>().ok().filter(|x| x.is_finite())).collect()
    };
    let rule = match verb {
        "in" if rest.starts_with('[') && rest.ends_with(']') => {
            match numbers(&rest[1..rest.len() - 1]).as_deref() {
                Some(&[lo, hi]) if lo <= hi => Rule::Range(lo, hi),
                _ => return invalid(),
            }
        }
        "in" if rest.starts_with('{') && rest.ends_with('}') => match numbers(&rest[1..rest.len() - 1]) {
            Some(values) if !values.is_empty() => Rule::Values(values),
            _ => return invalid(),
        },
        "length" => match rest.parse::<usize>() {
            Ok(n) if n > 0 => Rule::Length(n),
            _ => return invalid(),
        },
        _ => return invalid(),
    };
    Precondition { param: param.to_string(), rule }
}

/// The constraint on parameter `name`.
pub fn for_param(pre: &[Precondition], name: &str) -> Constraint {
    let mut c = Constraint::default();
    for p in pre.iter().filter(|p| p.param == name) {
        match &p.rule {
            Rule::Range(lo, hi) => c.range = Some((*lo, *hi)),
            Rule::Values(v) => c.values = Some(v.clone()),
            Rule::Length(n) => c.length = Some(*n),
            Rule::Invalid(_) => {}
        }
    }
    c
}

/// The clauses that did not parse.
pub fn invalid(pre: &[Precondition]) -> Vec<String> {
    pre.iter()
        .filter_map(|p| match &p.rule {
            Rule::Invalid(text) => Some(text.clone()),
            _ => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clauses_are_read_from_the_comment_directly_above() {
        let text = "// sweep: g in [0, 1]\n\n// unrelated\nfloat g() { return 0; }\n// The fbm.\n// sweep: octaves in [0, 16] (at most 16); n in {1, 2, 4}\n\
                    // sweep: clut length 6 (six colours)\nfloat f(float octaves, n; color clut[]) { return 0; }\n";
        let start = text.find("float f").unwrap();
        let pre = before(text, start);
        assert_eq!(for_param(&pre, "octaves").range, Some((0.0, 16.0)));
        assert_eq!(for_param(&pre, "n").values, Some(vec![1.0, 2.0, 4.0]));
        assert_eq!(for_param(&pre, "clut").length, Some(6));
        assert_eq!(for_param(&pre, "x"), Constraint::default());
        // A blank line ends the block above g; f's block is separated from it by g itself.
        assert!(before(text, text.find("float g").unwrap()).is_empty());
    }

    #[test]
    fn a_misspelt_clause_is_kept_as_invalid() {
        let text = "// sweep: octaves within [0, 16]; k in [3, 1]; n in [0, 1] x\nfloat f(float octaves) {}";
        let pre = before(text, text.find("float").unwrap());
        assert_eq!(invalid(&pre), ["octaves within [0, 16]", "k in [3, 1]", "n in [0, 1] x"]);
    }

    #[test]
    fn values_are_moved_into_the_constraint() {
        let c = Constraint { range: Some((0.0, 16.0)), ..Default::default() };
        assert_eq!((c.apply(-1e30), c.apply(3.5), c.apply(1e30)), (0.0, 3.5, 16.0));
        let c = Constraint { values: Some(vec![1.0, 2.0, 4.0]), ..Default::default() };
        assert_eq!((c.apply(-7.0), c.apply(2.9), c.apply(1e30)), (1.0, 2.0, 4.0));
    }
}
