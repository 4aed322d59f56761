//! Rust source text as the few tokens a module graph needs: identifiers,
//! `::`, brackets, punctuation and string literals, each with its line.
//! Comments (nested block comments too), character literals, lifetimes and
//! numbers are dropped; a string literal keeps its text (a `#[path = "..."]`
//! attribute needs it) but is never read as a path.

/// One token.
#[derive(Clone, Debug, PartialEq)]
pub enum Tok {
    /// An identifier or keyword (a raw identifier without its `r#`).
    Ident(String),
    /// A string literal's text between its quotes, escapes left as written.
    Str(String),
    /// `::`.
    PathSep,
    /// `(`, `[` or `{`.
    Open(char),
    /// `)`, `]` or `}`.
    Close(char),
    /// Any other punctuation character.
    Punct(char),
}

/// A token and the line it starts on (1-based).
#[derive(Clone, Debug, PartialEq)]
pub struct Token {
    /// The token.
    pub tok: Tok,
    /// Its line.
    pub line: usize,
}

fn is_ident_start(c: char) -> bool {
    c.is_alphabetic() || c == '_'
}

fn is_ident_char(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The tokens of `src`.
pub fn lex(src: &str) -> Vec<Token> {
    let c: Vec<char> = src.chars().collect();
    let at = |i: usize| c.get(i).copied().unwrap_or('\0');
    let mut out = Vec::new();
    let mut line = 1;
    let mut i = 0;
    while i < c.len() {
        let ch = c[i];
        if ch == '\n' {
            line += 1;
            i += 1;
        } else if ch.is_whitespace() {
            i += 1;
        } else if ch == '/' && at(i + 1) == '/' {
            while i < c.len() && c[i] != '\n' {
                i += 1;
            }
        } else if ch == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            while i < c.len() {
                if c[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    i += 2;
                } else if c[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    if c[i] == '\n' {
                        line += 1;
                    }
                    i += 1;
                }
            }
        } else if ch == '"' {
            let start = line;
            let (text, next) = quoted(&c, i + 1, &mut line);
            out.push(Token {
                tok: Tok::Str(text),
                line: start,
            });
            i = next;
        } else if ch == '\'' {
            i = char_or_lifetime(&c, i);
        } else if is_ident_start(ch) {
            let s = i;
            while i < c.len() && is_ident_char(c[i]) {
                i += 1;
            }
            let word: String = c[s..i].iter().collect();
            let raw = matches!(word.as_str(), "r" | "br" | "cr");
            if raw && (at(i) == '"' || (at(i) == '#' && (at(i + 1) == '"' || at(i + 1) == '#'))) {
                // A raw string: r"..", r#".."#, with as many hashes at the end.
                let mut hashes = 0;
                while at(i) == '#' {
                    hashes += 1;
                    i += 1;
                }
                i += 1;
                let start = line;
                let s = i;
                loop {
                    if i >= c.len() {
                        break;
                    }
                    if c[i] == '"' && (1..=hashes).all(|k| at(i + k) == '#') {
                        break;
                    }
                    if c[i] == '\n' {
                        line += 1;
                    }
                    i += 1;
                }
                out.push(Token {
                    tok: Tok::Str(c[s..i.min(c.len())].iter().collect()),
                    line: start,
                });
                i += 1 + hashes;
            } else if word == "r" && at(i) == '#' && is_ident_start(at(i + 1)) {
                // A raw identifier.
                i += 1;
                let s = i;
                while i < c.len() && is_ident_char(c[i]) {
                    i += 1;
                }
                out.push(Token {
                    tok: Tok::Ident(c[s..i].iter().collect()),
                    line,
                });
            } else if matches!(word.as_str(), "b" | "c") && at(i) == '"' {
                let start = line;
                let (text, next) = quoted(&c, i + 1, &mut line);
                out.push(Token {
                    tok: Tok::Str(text),
                    line: start,
                });
                i = next;
            } else if word == "b" && at(i) == '\'' {
                i = char_or_lifetime(&c, i);
            } else {
                out.push(Token {
                    tok: Tok::Ident(word),
                    line,
                });
            }
        } else if ch.is_ascii_digit() {
            while i < c.len()
                && (is_ident_char(c[i]) || (c[i] == '.' && at(i + 1).is_ascii_digit()))
            {
                i += 1;
            }
        } else if ch == ':' && at(i + 1) == ':' {
            out.push(Token {
                tok: Tok::PathSep,
                line,
            });
            i += 2;
        } else {
            let tok = match ch {
                '(' | '[' | '{' => Tok::Open(ch),
                ')' | ']' | '}' => Tok::Close(ch),
                _ => Tok::Punct(ch),
            };
            out.push(Token { tok, line });
            i += 1;
        }
    }
    out
}

/// The text of a string whose opening quote is just before `i`, and the
/// index after its closing quote.
fn quoted(c: &[char], mut i: usize, line: &mut usize) -> (String, usize) {
    let s = i;
    while i < c.len() && c[i] != '"' {
        if c[i] == '\\' {
            i += 1;
        }
        if i < c.len() && c[i] == '\n' {
            *line += 1;
        }
        i += 1;
    }
    (c[s..i.min(c.len())].iter().collect(), i + 1)
}

/// Skips a character literal or a lifetime starting at the quote `c[i]`.
fn char_or_lifetime(c: &[char], i: usize) -> usize {
    let at = |k: usize| c.get(k).copied().unwrap_or('\0');
    if at(i + 1) == '\\' {
        let mut k = i + 3;
        while k < c.len() && c[k] != '\'' {
            k += 1;
        }
        k + 1
    } else if at(i + 2) == '\'' {
        i + 3
    } else {
        let mut k = i + 1;
        while k < c.len() && is_ident_char(c[k]) {
            k += 1;
        }
        k
    }
}

#[test]
fn comments_strings_and_lifetimes_are_not_paths() {
    let src = "use a::b; // c::d\n/* e::f /* nested */ g::h */ let s = \"i::j\";\n\
               let r = r#\"k::\"l\"#; fn f<'a>(x: &'a str) -> char { '\\'' }\nm::n";
    let idents: Vec<(String, usize)> = lex(src)
        .into_iter()
        .filter_map(|t| match t.tok {
            Tok::Ident(s) => Some((s, t.line)),
            _ => None,
        })
        .collect();
    let names: Vec<&str> = idents.iter().map(|(s, _)| s.as_str()).collect();
    assert_eq!(
        names,
        ["use", "a", "b", "let", "s", "let", "r", "fn", "f", "x", "str", "char", "m", "n"]
    );
    // Lines survive comments and strings spanning lines.
    assert_eq!(idents.last().map(|(_, l)| *l), Some(4));
}
