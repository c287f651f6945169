//! `match(pattern, subject)`: a regular-expression search, decided when the program is compiled
//! (both strings are known then).
//!
//! RenderMan (RI spec 3.2, section 15.5): 1 if the pattern matches anywhere within the subject, 0
//! if not. This matcher covers the common subset of POSIX regular expressions: literal characters,
//! `.`, bracket expressions (`[abc]`, `[a-z]`, `[^...]`, a leading `]` literal), the repetitions
//! `*`, `+` and `?` after one item, `^` at the start and `$` at the end as anchors, and `\` to make
//! the next character literal. Groups, alternation and counted repetitions are refused, not
//! guessed at.
//!
//! Both backends fold `match` with this one matcher (its strings are known to both when they
//! lower the call), so they cannot disagree on what a pattern means.

/// One item of a pattern.
#[derive(Clone, Debug, PartialEq)]
enum Item {
    /// A character.
    Literal(char),
    /// `.`: any character.
    Any,
    /// A bracket expression: its ranges (a single character is a range of one), negated or not.
    Class { ranges: Vec<(char, char)>, negated: bool },
}

impl Item {
    fn matches(&self, c: char) -> bool {
        match self {
            Item::Literal(l) => *l == c,
            Item::Any => true,
            Item::Class { ranges, negated } => {
                ranges.iter().any(|(lo, hi)| (*lo..=*hi).contains(&c)) != *negated
            }
        }
    }
}

/// How many times an item may occur.
#[derive(Copy, Clone, Debug, PartialEq)]
enum Repeat {
    /// Exactly once.
    One,
    /// `*`.
    Any,
    /// `+`.
    Some,
    /// `?`.
    Optional,
}

/// A parsed pattern.
#[derive(Debug)]
struct Pattern {
    /// Anchored at the start (`^`).
    start: bool,
    /// Anchored at the end (`$`).
    end: bool,
    /// The items in order, each with its repetition.
    items: Vec<(Item, Repeat)>,
}

fn parse(pattern: &str) -> Result<Pattern, String> {
    let chars: Vec<char> = pattern.chars().collect();
    let mut i = 0;
    let start = chars.first() == Some(&'^');
    if start {
        i = 1;
    }
    // `$` anchors only as the last character (and not escaped); elsewhere it is literal, as in
    // POSIX basic expressions.
    let end = chars.len() > i && chars.last() == Some(&'$') && !escaped_at(&chars, chars.len() - 1);
    let stop = if end { chars.len() - 1 } else { chars.len() };
    let mut items: Vec<(Item, Repeat)> = Vec::new();
    while i < stop {
        let c = chars[i];
        let item = match c {
            '\\' => {
                i += 1;
                match chars.get(i) {
                    Some(&e) if i < stop => Item::Literal(e),
                    _ => return Err("the pattern ends with a lone `\\`".into()),
                }
            }
            '.' => Item::Any,
            '[' => {
                let (item, next) = class(&chars, i + 1)?;
                i = next - 1;
                item
            }
            '*' | '+' | '?' => {
                let repeat = match c {
                    '*' => Repeat::Any,
                    '+' => Repeat::Some,
                    _ => Repeat::Optional,
                };
                match items.last_mut() {
                    Some((_, r @ Repeat::One)) => *r = repeat,
                    // A repetition with nothing before it (or after another) is literal, as POSIX
                    // basic expressions read a leading `*`.
                    _ => items.push((Item::Literal(c), Repeat::One)),
                }
                i += 1;
                continue;
            }
            '(' | ')' | '|' | '{' => {
                return Err(format!("`{c}` (groups, alternation, counted repetition) is not supported"));
            }
            _ => Item::Literal(c),
        };
        items.push((item, Repeat::One));
        i += 1;
    }
    Ok(Pattern { start, end, items })
}

/// Whether the character at `at` is preceded by an odd number of backslashes.
fn escaped_at(chars: &[char], at: usize) -> bool {
    chars[..at].iter().rev().take_while(|c| **c == '\\').count() % 2 == 1
}

/// A bracket expression starting after its `[`: the item and the index after its `]`.
fn class(chars: &[char], mut i: usize) -> Result<(Item, usize), String> {
    let negated = chars.get(i) == Some(&'^');
    if negated {
        i += 1;
    }
    let mut ranges = Vec::new();
    let mut first = true;
    loop {
        let Some(&c) = chars.get(i) else {
            return Err("a `[` without its `]`".into());
        };
        if c == ']' && !first {
            return Ok((Item::Class { ranges, negated }, i + 1));
        }
        first = false;
        match (chars.get(i + 1), chars.get(i + 2)) {
            (Some('-'), Some(&hi)) if hi != ']' => {
                ranges.push((c, hi));
                i += 3;
            }
            _ => {
                ranges.push((c, c));
                i += 1;
            }
        }
    }
}

/// Whether `items` match a prefix of `s` that ends at the end of `s` when `end` is set.
fn match_here(items: &[(Item, Repeat)], s: &[char], end: bool) -> bool {
    let Some(((item, repeat), rest)) = items.split_first() else {
        return !end || s.is_empty();
    };
    let (least, most) = match repeat {
        Repeat::One => (1, 1),
        Repeat::Any => (0, usize::MAX),
        Repeat::Some => (1, usize::MAX),
        Repeat::Optional => (0, 1),
    };
    // How many characters from here the item can take; then try the longest first.
    let available = s.iter().take(most).take_while(|c| item.matches(**c)).count();
    (least..=available).rev().any(|n| match_here(rest, &s[n..], end))
}

/// Whether `pattern` matches somewhere in `subject`; an error describes a pattern outside the
/// supported subset.
pub(crate) fn search(pattern: &str, subject: &str) -> Result<bool, String> {
    let p = parse(pattern)?;
    let s: Vec<char> = subject.chars().collect();
    if p.start {
        return Ok(match_here(&p.items, &s, p.end));
    }
    Ok((0..=s.len()).any(|at| match_here(&p.items, &s[at..], p.end)))
}

#[cfg(test)]
mod tests {
    use super::search;

    fn yes(p: &str, s: &str) {
        assert_eq!(search(p, s), Ok(true), "{p:?} should match {s:?}");
    }

    fn no(p: &str, s: &str) {
        assert_eq!(search(p, s), Ok(false), "{p:?} should not match {s:?}");
    }

    #[test]
    fn literals_search_anywhere() {
        yes("wood", "darkwood_2");
        yes("", "anything");
        no("wood", "woo");
    }

    #[test]
    fn anchors() {
        yes("^dark", "darkwood");
        no("^wood", "darkwood");
        yes("wood$", "darkwood");
        no("dark$", "darkwood");
        yes("^$", "");
        no("^$", "x");
        yes("a$b", "a$b");
    }

    #[test]
    fn dot_and_repetitions() {
        yes("d.rk", "dark");
        yes("^a*b$", "b");
        yes("^a*b$", "aaab");
        no("^a+b$", "b");
        yes("^a+b$", "ab");
        yes("^colou?r$", "color");
        yes("^colou?r$", "colour");
        no("^colou?r$", "colouur");
        yes("^.*_spec$", "metal_spec");
        yes("*x", "a*x");
    }

    #[test]
    fn classes() {
        yes("^[a-c]+$", "abcab");
        no("^[a-c]+$", "abd");
        yes("^[^0-9]*$", "abc");
        no("^[^0-9]*$", "a1");
        yes("[]]", "a]");
        yes("[a-]", "-");
    }

    #[test]
    fn escapes() {
        yes("a\\.b", "a.b");
        no("a\\.b", "axb");
        yes("\\$$", "cost$");
    }

    #[test]
    fn unsupported_patterns_are_errors() {
        assert!(search("(ab)", "ab").is_err());
        assert!(search("a|b", "a").is_err());
        assert!(search("[ab", "a").is_err());
        assert!(search("ab\\", "ab").is_err());
    }
}
