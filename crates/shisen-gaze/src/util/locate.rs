//! Where a field is written in RON text: the line and column of the key
//! (or list element) a path such as `timeline[2].do.Punch.speed` names.
//!
//! Errors found after a file is read (a value outside its range, a check
//! across fields) know the field's path but not its place. A small scanner
//! walks the text's structure (comments and strings skipped, so a word in
//! a comment is never taken for the field) and records where each path
//! starts. Type and variant names (`Scene(`, `Punch(`, `Some(`) are written
//! in RON but are not fields, so the scanner files places without them;
//! a path's capitalised segments may be either such a name (a variant in
//! `timeline[2].do.Punch.speed`) or a map's key (`onset.Surprise.upper`),
//! and the search tries both.
//!
//! The scanner also finds numbers that are not finite (`NaN`, `inf`,
//! `1e999`): serialised for the range check they become `null`, which an
//! optional field allows, so they are refused here, where they are written.

use std::collections::HashMap;

/// Whether a path segment may be a type or variant name.
fn capitalised(s: &str) -> bool {
    s.starts_with(|c: char| c.is_ascii_uppercase())
}

/// Split a dotted path (`vh.neck.kp`, `timeline[2].do.Punch.speed`) or a
/// JSON pointer (`/timeline/2/do/Punch/speed`) into segments.
pub fn segments(path: &str) -> Vec<String> {
    if let Some(pointer) = path.strip_prefix('/') {
        return pointer
            .split('/')
            .map(|s| s.replace("~1", "/").replace("~0", "~"))
            .collect();
    }
    path.split(['.', '[', ']'])
        .filter(|s| !s.is_empty() && *s != "-")
        .map(str::to_string)
        .collect()
}

/// The places of every path written in one RON text.
#[derive(Debug, Default)]
pub struct Locations {
    at: HashMap<Vec<String>, (usize, usize)>,
    non_finite: Vec<(Vec<Seg>, usize, usize)>,
}

/// A path segment as written: a field, key or index, or a variant's name
/// (shown in messages, not part of the key places are filed under).
type Seg = (String, bool);

/// The key a path is filed under: its segments without variant names.
fn key_of(path: &[Seg]) -> Vec<String> {
    path.iter()
        .filter(|(_, variant)| !variant)
        .map(|(s, _)| s.clone())
        .collect()
}

impl Locations {
    /// Scan `text`. Malformed text is scanned as far as it goes (the
    /// parser reports its syntax errors itself).
    pub fn scan(text: &str) -> Locations {
        Scanner::new(text).run()
    }

    /// 1-based `(line, col)` of `path` (dotted or a JSON pointer), or of
    /// the nearest enclosing field that is written (a field left to its
    /// default is reported where its parent is); `(1, 1)` if none is.
    pub fn find(&self, path: &str) -> (usize, usize) {
        let segs = segments(path);
        let caps: Vec<usize> = (0..segs.len()).filter(|&i| capitalised(&segs[i])).collect();
        // Each capitalised segment kept (a map's key) or dropped (a
        // variant's name); the deepest place found wins. At most 2^8 tries.
        let tries = 1usize << caps.len().min(8);
        let mut best: Option<(usize, (usize, usize))> = None;
        for mask in 0..tries {
            let keep = |i: usize| {
                caps.iter()
                    .position(|&c| c == i)
                    .is_none_or(|k| k >= 8 || mask & (1 << k) != 0)
            };
            let mut key: Vec<String> = Vec::new();
            let mut found = (0, self.at.get(&key).copied());
            for (i, s) in segs.iter().enumerate() {
                if !keep(i) {
                    continue;
                }
                key.push(s.clone());
                if let Some(&p) = self.at.get(&key) {
                    found = (i + 1, Some(p));
                }
            }
            if let (depth, Some(p)) = found
                && best.is_none_or(|(d, _)| depth > d)
            {
                best = Some((depth, p));
            }
        }
        best.map_or((1, 1), |(_, p)| p)
    }

    /// The first number written that is not finite: its dotted path and
    /// 1-based `(line, col)`.
    pub fn non_finite(&self) -> Option<(String, usize, usize)> {
        self.non_finite
            .first()
            .map(|(path, line, col)| (dotted(path.iter().map(|(s, _)| s.as_str())), *line, *col))
    }
}

/// Segments written as a dotted path (`timeline[2].do.Punch.speed`), `-`
/// for none.
pub fn dotted<'a>(segments: impl IntoIterator<Item = &'a str>) -> String {
    let mut out = String::new();
    for s in segments {
        if s.bytes().all(|b| b.is_ascii_digit()) {
            out.push_str(&format!("[{s}]"));
        } else {
            if !out.is_empty() {
                out.push('.');
            }
            out.push_str(s);
        }
    }
    if out.is_empty() { "-".into() } else { out }
}

/// Shorthand for `Locations::scan(text).find(path)`.
pub fn locate(text: &str, path: &str) -> (usize, usize) {
    Locations::scan(text).find(path)
}

#[derive(Clone, Copy, PartialEq)]
enum Open {
    Paren,
    Bracket,
    Brace,
}

struct Frame {
    open: Open,
    /// Path of the value this frame is the inside of.
    base: Vec<Seg>,
    /// Position of the next element (lists, tuples).
    index: usize,
    /// The key whose value is being read (structs, maps).
    key: Option<String>,
    /// `Some(...)`: its one element is the value itself, not an index.
    transparent: bool,
    /// Opened by a name (`Point(`): a first element that is itself a tuple
    /// or list is a newtype's content (`Point((x, y, z))`), not index 0.
    named: bool,
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    Str(String),
    Punct(char),
    Other(String),
}

struct Scanner<'a> {
    src: &'a [u8],
    pos: usize,
    line: usize,
    col: usize,
    toks: Vec<(Tok, usize, usize)>,
}

impl<'a> Scanner<'a> {
    fn new(text: &'a str) -> Self {
        Scanner {
            src: text.as_bytes(),
            pos: 0,
            line: 1,
            col: 1,
            toks: Vec::new(),
        }
    }

    fn bump(&mut self) -> Option<u8> {
        let c = *self.src.get(self.pos)?;
        self.pos += 1;
        if c == b'\n' {
            self.line += 1;
            self.col = 1;
        } else if c & 0xC0 != 0x80 {
            // Columns count characters, not UTF-8 continuation bytes.
            self.col += 1;
        }
        Some(c)
    }

    fn peek(&self, k: usize) -> Option<u8> {
        self.src.get(self.pos + k).copied()
    }

    fn tokenize(&mut self) {
        while let Some(c) = self.peek(0) {
            let (line, col) = (self.line, self.col);
            match c {
                b'/' if self.peek(1) == Some(b'/') => {
                    while self.peek(0).is_some_and(|c| c != b'\n') {
                        self.bump();
                    }
                }
                b'/' if self.peek(1) == Some(b'*') => {
                    // RON's block comments nest.
                    let mut depth = 0usize;
                    loop {
                        match (self.peek(0), self.peek(1)) {
                            (Some(b'/'), Some(b'*')) => {
                                depth += 1;
                                self.bump();
                                self.bump();
                            }
                            (Some(b'*'), Some(b'/')) => {
                                depth -= 1;
                                self.bump();
                                self.bump();
                                if depth == 0 {
                                    break;
                                }
                            }
                            (Some(_), _) => {
                                self.bump();
                            }
                            (None, _) => break,
                        }
                    }
                }
                b'"' => {
                    self.bump();
                    let start = self.pos;
                    while let Some(c) = self.peek(0) {
                        if c == b'\\' {
                            self.bump();
                        } else if c == b'"' {
                            break;
                        }
                        self.bump();
                    }
                    let s = String::from_utf8_lossy(&self.src[start..self.pos]).into_owned();
                    self.bump();
                    self.toks.push((Tok::Str(s), line, col));
                }
                b'r' if matches!(self.peek(1), Some(b'"' | b'#')) => {
                    // A raw string r#"..."#.
                    self.bump();
                    let mut hashes = 0;
                    while self.peek(0) == Some(b'#') {
                        hashes += 1;
                        self.bump();
                    }
                    self.bump();
                    'raw: while self.peek(0).is_some() {
                        if self.peek(0) == Some(b'"')
                            && (1..=hashes).all(|k| self.peek(k) == Some(b'#'))
                        {
                            for _ in 0..=hashes {
                                self.bump();
                            }
                            break 'raw;
                        }
                        self.bump();
                    }
                    self.toks.push((Tok::Other(String::new()), line, col));
                }
                b'\'' => {
                    self.bump();
                    while let Some(c) = self.bump() {
                        if c == b'\\' {
                            self.bump();
                        } else if c == b'\'' {
                            break;
                        }
                    }
                    self.toks.push((Tok::Other(String::new()), line, col));
                }
                b'(' | b')' | b'[' | b']' | b'{' | b'}' | b':' | b',' => {
                    self.bump();
                    self.toks.push((Tok::Punct(c as char), line, col));
                }
                c if c.is_ascii_alphabetic() || c == b'_' => {
                    let start = self.pos;
                    while self
                        .peek(0)
                        .is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_')
                    {
                        self.bump();
                    }
                    let s = String::from_utf8_lossy(&self.src[start..self.pos]).into_owned();
                    self.toks.push((Tok::Ident(s), line, col));
                }
                c if c.is_ascii_whitespace() => {
                    self.bump();
                }
                _ => {
                    // Numbers, signs and anything else: one token per run
                    // (at least one byte, so the scan always moves on).
                    let start = self.pos;
                    self.bump();
                    while self
                        .peek(0)
                        .is_some_and(|c| !c.is_ascii_whitespace() && !b"()[]{}:,/\"'".contains(&c))
                    {
                        self.bump();
                    }
                    let t = String::from_utf8_lossy(&self.src[start..self.pos]).into_owned();
                    self.toks.push((Tok::Other(t), line, col));
                }
            }
        }
    }

    fn run(mut self) -> Locations {
        self.tokenize();
        let toks = std::mem::take(&mut self.toks);
        let mut at: HashMap<Vec<String>, (usize, usize)> = HashMap::new();
        let mut non_finite = Vec::new();
        let mut record = |path: &[Seg], line: usize, col: usize| {
            at.entry(key_of(path)).or_insert((line, col));
        };
        // The root value's inside.
        let mut stack: Vec<Frame> = Vec::new();
        // Path of the value about to be read, once its place is known.
        let mut value_path: Vec<Seg> = Vec::new();
        let mut i = 0;
        while i < toks.len() {
            let (tok, line, col) = &toks[i];
            let next = toks.get(i + 1).map(|t| &t.0);
            // Where a value starts inside a positional frame (list, tuple),
            // its path is the frame's base and its index.
            if let Some(f) = stack.last_mut()
                && f.key.is_none()
                && !matches!(tok, Tok::Punct(')' | ']' | '}' | ','))
                && !(f.open == Open::Paren && matches!(next, Some(Tok::Punct(':'))))
                && !(f.open == Open::Brace)
                && value_path.is_empty()
            {
                value_path = f.base.clone();
                let newtype = f.named && f.index == 0 && matches!(tok, Tok::Punct('(' | '['));
                if !f.transparent && !newtype {
                    value_path.push((f.index.to_string(), false));
                }
                record(&value_path, *line, *col);
            }
            match tok {
                Tok::Ident(name) | Tok::Str(name) if matches!(next, Some(Tok::Punct(':'))) => {
                    if let Some(f) = stack.last_mut() {
                        let mut p = f.base.clone();
                        p.push((name.clone(), false));
                        record(&p, *line, *col);
                        f.key = Some(name.clone());
                        value_path = p;
                    }
                    i += 2;
                    continue;
                }
                Tok::Ident(name) if matches!(next, Some(Tok::Punct('('))) => {
                    // A struct's or variant's name before its body: not a
                    // field, so not part of the key (the root's type name
                    // and `Some` are not shown either).
                    let mut p = std::mem::take(&mut value_path);
                    record(&p, *line, *col);
                    if !stack.is_empty() && name != "Some" {
                        p.push((name.clone(), true));
                    }
                    stack.push(Frame {
                        open: Open::Paren,
                        base: p,
                        index: 0,
                        key: None,
                        transparent: name == "Some",
                        named: true,
                    });
                    i += 2;
                    continue;
                }
                Tok::Punct(c @ ('(' | '[' | '{')) => {
                    let open = match c {
                        '(' => Open::Paren,
                        '[' => Open::Bracket,
                        _ => Open::Brace,
                    };
                    stack.push(Frame {
                        open,
                        base: std::mem::take(&mut value_path),
                        index: 0,
                        key: None,
                        transparent: false,
                        named: false,
                    });
                }
                Tok::Punct(')' | ']' | '}') => {
                    stack.pop();
                    value_path.clear();
                }
                Tok::Punct(',') => {
                    if let Some(f) = stack.last_mut()
                        && f.key.take().is_none()
                    {
                        f.index += 1;
                    }
                    value_path.clear();
                }
                Tok::Ident(t) | Tok::Other(t) if t.parse::<f64>().is_ok_and(|x| !x.is_finite()) => {
                    non_finite.push((value_path.clone(), *line, *col));
                    value_path.clear();
                }
                _ => {
                    // A plain value ends the path it was read for.
                    value_path.clear();
                }
            }
            i += 1;
        }
        Locations { at, non_finite }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = r#"// a2 in a comment: not the field
Scene(
  name: "a2 in a string", /* a2 */
  vh: (
    personality: (a1: 1.0, a2: 0.5),
  ),
  timeline: [
    (at: 0.0, do: Punch(hand: Left)),
    (at: 1.0, do: Track(body: "ball", until: 2.0)),
  ],
  bodies: [Body(name: "ball", pos: [0, 1, 2])],
  bindings: {"Space": Jab, "q": Guard},
)
"#;

    #[test]
    fn fields_are_found_where_written_not_in_comments_or_strings() {
        let loc = Locations::scan(TEXT);
        assert_eq!(loc.find("vh.personality.a2"), (5, 28));
        assert_eq!(loc.find("/vh/personality/a2"), (5, 28));
        assert_eq!(loc.find("timeline[1].do.Track.until"), (9, 39));
        assert_eq!(loc.find("timeline[1]"), (9, 5));
        assert_eq!(loc.find("timeline[0].do.Punch.hand"), (8, 25));
        assert_eq!(loc.find("bodies[0].pos"), (11, 31));
        assert_eq!(loc.find("bindings.q"), (12, 28));
        assert_eq!(loc.find("bindings.Space"), (12, 14));
    }

    #[test]
    fn a_field_left_to_its_default_is_found_at_its_parent() {
        let loc = Locations::scan(TEXT);
        assert_eq!(loc.find("vh.personality.a9"), (5, 5));
        assert_eq!(loc.find("nothing.here"), (2, 1));
    }

    #[test]
    fn broken_text_does_not_panic() {
        for cut in 0..TEXT.len() {
            if TEXT.is_char_boundary(cut) {
                let _ = Locations::scan(&TEXT[..cut]).find("vh.personality.a2");
            }
        }
        let _ = Locations::scan("))]]}},,::r#\"x\"# 'a' /* /* */");
    }

    #[test]
    fn capitalised_map_keys_are_told_from_variant_names() {
        let text = "(\n  onset: {\n    Happiness: (upper: 1.0),\n    Surprise: (upper: 2.0),\n  },\n  do: Punch(speed: 3.0),\n)";
        let loc = Locations::scan(text);
        assert_eq!(loc.find("onset.Surprise.upper"), (4, 16));
        assert_eq!(loc.find("/onset/Happiness/upper"), (3, 17));
        assert_eq!(loc.find("do.Punch.speed"), (6, 13));
        let loc = Locations::scan("(t: Point((0.0, 500.0, 0.0)), u: Point(1.0, 2.0, 3.0))");
        assert_eq!(loc.find("/t/Point/1"), (1, 17));
        assert_eq!(loc.find("/u/Point/2"), (1, 50));
        let loc = Locations::scan("(\n gains: Some(Gains(\n  neck: (kp: -3.0),\n )),\n)");
        assert_eq!(loc.find("gains.neck.kp"), (3, 10));
    }

    #[test]
    fn numbers_that_are_not_finite_are_found_where_written() {
        let loc = Locations::scan("(a: 1.0, b: [2.0, NaN], c: (d: -inf), e: 1e999)");
        assert_eq!(loc.non_finite(), Some(("b[1]".to_string(), 1, 19)));
        assert_eq!(
            Locations::scan("Scene(t: [(do: Punch(speed: NaN))])").non_finite(),
            Some(("t[0].do.Punch.speed".to_string(), 1, 29))
        );
        assert_eq!(Locations::scan("(a: 1.0, s: \"NaN\")").non_finite(), None);
        assert_eq!(
            Locations::scan("(c: (d: -inf))").non_finite(),
            Some(("c.d".to_string(), 1, 9))
        );
    }
}
