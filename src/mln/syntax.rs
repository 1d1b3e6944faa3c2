//! The text formats: tokens, and the syntax trees of knowledge-base and evidence lines.
//!
//! This layer knows the grammar only; which names are predicates, types, variables or
//! constants is decided in [`super::kb`], which resolves the trees against the declarations.
//!
//! One statement per line. Operator precedence, tightest first: `!`, `^`, `v`, `=>`, `<=>`;
//! `=>` groups to the right, the others to the left. A quantifier (`EXIST x,y` or
//! `FORALL x`) reaches as far right as it can (to the end of the line or of the enclosing
//! parenthesis).

use super::error::{MlnError, Position};

#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Tok {
    Ident(String),
    Number(f64),
    LParen,
    RParen,
    LBrace,
    RBrace,
    Comma,
    Not,
    And,
    Implies,
    Equiv,
    Eq,
    NotEq,
    Dot,
    Plus,
    Minus,
    Star,
    Slash,
    Newline,
    Eof,
}

#[derive(Debug, Clone)]
pub(crate) struct Token {
    pub tok: Tok,
    pub at: Position,
    /// Byte range in the source.
    pub start: usize,
    pub end: usize,
}

/// How a token reads in an error message.
fn describe(t: &Token, src: &str) -> String {
    match &t.tok {
        Tok::Newline => "end of line".into(),
        Tok::Eof => "end of input".into(),
        _ => format!("'{}'", &src[t.start..t.end]),
    }
}

/// The index after the run of characters from `i` on that satisfy `keep`.
fn digits_end(chars: &[(usize, char)], i: usize, keep: impl Fn(char) -> bool) -> usize {
    let mut j = i;
    while j < chars.len() && keep(chars[j].1) {
        j += 1;
    }
    j
}

/// The index after the number starting at `i`: digits, an optional fraction, an optional
/// exponent (`e`, a sign, digits; an `e` without digits is not part of the number).
fn number_end(chars: &[(usize, char)], i: usize) -> usize {
    let digit = |c: char| c.is_ascii_digit();
    let mut j = digits_end(chars, i, digit);
    if j < chars.len() && chars[j].1 == '.' && chars.get(j + 1).is_some_and(|d| d.1.is_ascii_digit()) {
        j = digits_end(chars, j + 1, digit);
    }
    if j < chars.len() && matches!(chars[j].1, 'e' | 'E') {
        let mut k = j + 1;
        if k < chars.len() && matches!(chars[k].1, '+' | '-') {
            k += 1;
        }
        if k < chars.len() && chars[k].1.is_ascii_digit() {
            j = digits_end(chars, k, digit);
        }
    }
    j
}

/// The index of the `*/` closing the block comment that opens at `i`, and whether the comment
/// spans lines; `line` and `col` follow the characters inside it.
fn block_comment_end(
    chars: &[(usize, char)],
    i: usize,
    at: Position,
    line: &mut u32,
    col: &mut u32,
) -> Result<(usize, bool), MlnError> {
    let mut j = i + 2;
    let mut newline = false;
    while j < chars.len() && !(chars[j].1 == '*' && chars.get(j + 1).map(|c| c.1) == Some('/')) {
        if chars[j].1 == '\n' {
            newline = true;
            *line += 1;
            *col = 0;
        }
        j += 1;
        *col += 1;
    }
    if j >= chars.len() {
        return Err(MlnError::syntax(at, "'*/' to close this comment", "end of input"));
    }
    Ok((j, newline))
}

/// The error for a character `c` at `at` that starts no token.
fn unexpected_char(at: Position, c: char) -> MlnError {
    let hint = if c == '#' { " (directives such as #include are not supported)" } else { "" };
    MlnError::syntax(
        at,
        format!("a name, a number, a connective (! ^ v => <=>) or a parenthesis{hint}"),
        format!("'{c}'"),
    )
}

/// Splits a text into tokens; `//` and `/* */` comments are dropped, line ends kept.
pub(crate) fn lex(src: &str) -> Result<Vec<Token>, MlnError> {
    let mut out = Vec::new();
    let chars: Vec<(usize, char)> = src.char_indices().collect();
    let (mut line, mut col) = (1u32, 1u32);
    let mut i = 0;
    let byte = |i: usize| chars.get(i).map_or(src.len(), |c| c.0);
    while i < chars.len() {
        let c = chars[i].1;
        let at = Position { line, column: col };
        let start = chars[i].0;
        let next = chars.get(i + 1).map(|c| c.1);
        let push = |tok: Tok, n: usize, out: &mut Vec<Token>| {
            out.push(Token { tok, at, start, end: byte(i + n) });
            n
        };
        let n = match c {
            '\n' => {
                push(Tok::Newline, 1, &mut out);
                i += 1;
                line += 1;
                col = 1;
                continue;
            }
            c if c.is_whitespace() => 1,
            '/' if next == Some('/') => digits_end(&chars, i, |c| c != '\n') - i,
            '/' if next == Some('*') => {
                let (j, newline) = block_comment_end(&chars, i, at, &mut line, &mut col)?;
                if newline {
                    out.push(Token { tok: Tok::Newline, at, start, end: byte(j + 2) });
                }
                i = j + 2;
                col += 2;
                continue;
            }
            '(' => push(Tok::LParen, 1, &mut out),
            ')' => push(Tok::RParen, 1, &mut out),
            '{' => push(Tok::LBrace, 1, &mut out),
            '}' => push(Tok::RBrace, 1, &mut out),
            ',' => push(Tok::Comma, 1, &mut out),
            '^' => push(Tok::And, 1, &mut out),
            '+' => push(Tok::Plus, 1, &mut out),
            '-' => push(Tok::Minus, 1, &mut out),
            '*' => push(Tok::Star, 1, &mut out),
            '/' => push(Tok::Slash, 1, &mut out),
            '!' if next == Some('=') => push(Tok::NotEq, 2, &mut out),
            '!' => push(Tok::Not, 1, &mut out),
            '=' if next == Some('>') => push(Tok::Implies, 2, &mut out),
            '=' => push(Tok::Eq, 1, &mut out),
            '<' if next == Some('=') && chars.get(i + 2).map(|c| c.1) == Some('>') => push(Tok::Equiv, 3, &mut out),
            '.' if !next.is_some_and(|d| d.is_ascii_digit()) => push(Tok::Dot, 1, &mut out),
            c if c.is_ascii_digit() || c == '.' => {
                let j = number_end(&chars, i);
                let text = &src[start..byte(j)];
                let v: f64 = text.parse().map_err(|_| MlnError::syntax(at, "a number", format!("'{text}'")))?;
                push(Tok::Number(v), j - i, &mut out)
            }
            c if c.is_alphabetic() || c == '_' => {
                let j = digits_end(&chars, i, |c| c.is_alphanumeric() || c == '_');
                let name = src[start..byte(j)].to_string();
                push(Tok::Ident(name), j - i, &mut out)
            }
            c => return Err(unexpected_char(at, c)),
        };
        i += n;
        col += n as u32;
    }
    let at = Position { line, column: col };
    out.push(Token { tok: Tok::Eof, at, start: src.len(), end: src.len() });
    Ok(out)
}

/// A name or number in an argument list, with where it stands.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Name {
    pub text: String,
    pub at: Position,
}

impl Name {
    /// Variables start with a lower-case letter or `_`; constants with a capital or a digit.
    pub fn is_variable(&self) -> bool {
        self.text.chars().next().is_some_and(|c| c.is_lowercase() || c == '_')
    }
}

/// A formula as written, before names are resolved.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Raw {
    Atom { name: Name, args: Vec<Name> },
    Eq { left: Name, right: Name, negated: bool },
    Not(Box<Raw>),
    And(Vec<Raw>),
    Or(Vec<Raw>),
    Implies(Box<Raw>, Box<Raw>),
    Equiv(Box<Raw>, Box<Raw>),
    Quant { exists: bool, vars: Vec<Name>, body: Box<Raw> },
}

/// One line of a knowledge base.
#[derive(Debug, Clone)]
pub(crate) enum Statement {
    /// `type = {A, B, C}`
    Domain { name: Name, constants: Vec<Name> },
    /// `[weight] formula [.]`; a bare atom without weight or period is a declaration,
    /// which [`super::kb`] decides.
    Formula { weight: Option<f64>, hard: bool, formula: Raw, at: Position, text: String },
}

/// One line of an evidence database.
#[derive(Debug, Clone)]
pub(crate) struct EvidenceLine {
    pub probability: Option<f64>,
    pub negated: bool,
    pub predicate: Name,
    pub args: Vec<Name>,
}

struct Parser<'a> {
    src: &'a str,
    toks: Vec<Token>,
    i: usize,
    /// Recursion depth, bounded so that hostile input cannot overflow the stack.
    depth: u32,
}

/// Most nested parentheses, negations, implications and quantifiers in one statement.
const MAX_DEPTH: u32 = 200;

const QUANTIFIERS: [&str; 4] = ["EXIST", "exist", "FORALL", "forall"];
const FUNCTIONS: [&str; 3] = ["log", "ln", "exp"];

impl<'a> Parser<'a> {
    fn new(src: &'a str) -> Result<Self, MlnError> {
        Ok(Parser { src, toks: lex(src)?, i: 0, depth: 0 })
    }

    fn peek(&self) -> &Tok {
        &self.toks[self.i].tok
    }

    fn peek_at(&self, k: usize) -> &Tok {
        &self.toks[(self.i + k).min(self.toks.len() - 1)].tok
    }

    fn token(&self) -> &Token {
        &self.toks[self.i]
    }

    fn advance(&mut self) -> Token {
        let t = self.toks[self.i].clone();
        if self.i + 1 < self.toks.len() {
            self.i += 1;
        }
        t
    }

    /// Runs `f` one level deeper, refusing to go past [`MAX_DEPTH`].
    fn nested<T>(&mut self, f: impl FnOnce(&mut Self) -> Result<T, MlnError>) -> Result<T, MlnError> {
        if self.depth >= MAX_DEPTH {
            return Err(self.error(format!(
                "less nesting (at most {MAX_DEPTH} levels of parentheses, negations or implications)"
            )));
        }
        self.depth += 1;
        let r = f(self);
        self.depth -= 1;
        r
    }

    fn error(&self, expected: impl Into<String>) -> MlnError {
        let t = self.token();
        MlnError::syntax(t.at, expected, describe(t, self.src))
    }

    fn at_line_end(&self) -> bool {
        matches!(self.peek(), Tok::Newline | Tok::Eof)
    }

    fn is_ident(&self, k: usize, names: &[&str]) -> bool {
        matches!(self.peek_at(k), Tok::Ident(s) if names.contains(&s.as_str()))
    }

    /// A name or a number used as a name (constants may be integers).
    fn name(&mut self, expected: &str) -> Result<Name, MlnError> {
        let t = self.token().clone();
        match &t.tok {
            Tok::Ident(s) => {
                self.advance();
                Ok(Name { text: s.clone(), at: t.at })
            }
            Tok::Number(v) if v.fract() == 0.0 && self.src[t.start..t.end].bytes().all(|b| b.is_ascii_digit()) => {
                self.advance();
                Ok(Name { text: self.src[t.start..t.end].to_string(), at: t.at })
            }
            _ => Err(self.error(expected)),
        }
    }

    /// `( name, name, ... )` after a predicate name.
    fn arguments(&mut self, predicate: &str) -> Result<Vec<Name>, MlnError> {
        self.advance(); // '('
        let mut args = vec![self.name(&format!("a variable or constant as argument of {predicate}"))?];
        loop {
            match self.peek() {
                Tok::Comma => {
                    self.advance();
                    args.push(self.name(&format!("a variable or constant as argument of {predicate}"))?);
                }
                Tok::RParen => {
                    self.advance();
                    return Ok(args);
                }
                _ => return Err(self.error(format!("')' after the arguments of {predicate}"))),
            }
        }
    }

    // ----- formulas -----

    fn formula(&mut self) -> Result<Raw, MlnError> {
        let mut left = self.implication()?;
        while *self.peek() == Tok::Equiv {
            self.advance();
            let right = self.implication()?;
            left = Raw::Equiv(Box::new(left), Box::new(right));
        }
        Ok(left)
    }

    fn implication(&mut self) -> Result<Raw, MlnError> {
        let left = self.disjunction()?;
        if *self.peek() == Tok::Implies {
            self.advance();
            let right = self.nested(|p| p.implication())?;
            return Ok(Raw::Implies(Box::new(left), Box::new(right)));
        }
        Ok(left)
    }

    fn disjunction(&mut self) -> Result<Raw, MlnError> {
        let mut items = vec![self.conjunction()?];
        while self.is_ident(0, &["v"]) {
            self.advance();
            items.push(self.conjunction()?);
        }
        Ok(if items.len() == 1 { items.pop().unwrap() } else { Raw::Or(items) })
    }

    fn conjunction(&mut self) -> Result<Raw, MlnError> {
        let mut items = vec![self.unary()?];
        while *self.peek() == Tok::And {
            self.advance();
            items.push(self.unary()?);
        }
        Ok(if items.len() == 1 { items.pop().unwrap() } else { Raw::And(items) })
    }

    fn unary(&mut self) -> Result<Raw, MlnError> {
        if *self.peek() == Tok::Not {
            self.advance();
            return Ok(Raw::Not(Box::new(self.nested(|p| p.unary())?)));
        }
        self.primary()
    }

    fn primary(&mut self) -> Result<Raw, MlnError> {
        let t = self.token().clone();
        match &t.tok {
            Tok::LParen => {
                self.advance();
                let f = self.nested(|p| p.formula())?;
                if *self.peek() != Tok::RParen {
                    let at = t.at;
                    return Err(self.error(format!(
                        "a connective or ')' to close the '(' at line {}, column {}",
                        at.line, at.column
                    )));
                }
                self.advance();
                Ok(f)
            }
            Tok::Ident(s) if QUANTIFIERS.contains(&s.as_str()) && matches!(self.peek_at(1), Tok::Ident(_)) => {
                let exists = s.eq_ignore_ascii_case("exist");
                self.advance();
                let mut vars = vec![self.name("a variable after the quantifier")?];
                while *self.peek() == Tok::Comma {
                    self.advance();
                    vars.push(self.name("a variable after ','")?);
                }
                if let Some(c) = vars.iter().find(|v| !v.is_variable()) {
                    return Err(MlnError::syntax(
                        c.at,
                        "a variable (lower case) after the quantifier",
                        format!("'{}'", c.text),
                    ));
                }
                let body = self.nested(|p| p.formula())?;
                Ok(Raw::Quant { exists, vars, body: Box::new(body) })
            }
            Tok::Ident(_) | Tok::Number(_) if matches!(self.peek_at(1), Tok::Eq | Tok::NotEq) => {
                let left = self.name("a term")?;
                let negated = self.advance().tok == Tok::NotEq;
                let right = self.name("a variable or constant after the equality sign")?;
                Ok(Raw::Eq { left, right, negated })
            }
            Tok::Ident(s) => {
                if *self.peek_at(1) != Tok::LParen {
                    self.advance();
                    return Err(self.error(format!("'(' and the arguments of {s}")));
                }
                let name = Name { text: s.clone(), at: t.at };
                self.advance();
                let args = self.arguments(&name.text)?;
                Ok(Raw::Atom { name, args })
            }
            _ => Err(self.error("a formula (an atom such as Pred(x), '!', '(' or a quantifier)")),
        }
    }

    // ----- weights -----

    /// Whether the line starts with an arithmetic weight rather than a formula.
    fn looks_like_weight(&self) -> bool {
        let mut k = 0;
        loop {
            match self.peek_at(k) {
                Tok::Number(_) | Tok::Minus | Tok::Plus => return true,
                Tok::LParen => k += 1,
                Tok::Ident(s) if FUNCTIONS.contains(&s.as_str()) && *self.peek_at(k + 1) == Tok::LParen => {
                    // `log(0.9/0.1)` is a weight, `log(x)` an atom of a predicate called log.
                    return matches!(self.peek_at(k + 2), Tok::Number(_) | Tok::LParen | Tok::Minus | Tok::Plus)
                        || matches!(self.peek_at(k + 2), Tok::Ident(f) if FUNCTIONS.contains(&f.as_str()));
                }
                _ => return false,
            }
        }
    }

    fn weight_sum(&mut self) -> Result<f64, MlnError> {
        let mut v = self.weight_product()?;
        loop {
            match self.peek() {
                Tok::Plus => {
                    self.advance();
                    v += self.weight_product()?;
                }
                Tok::Minus => {
                    self.advance();
                    v -= self.weight_product()?;
                }
                _ => return Ok(v),
            }
        }
    }

    fn weight_product(&mut self) -> Result<f64, MlnError> {
        let mut v = self.weight_unary()?;
        loop {
            match self.peek() {
                Tok::Star => {
                    self.advance();
                    v *= self.weight_unary()?;
                }
                Tok::Slash => {
                    let at = self.advance().at;
                    let d = self.weight_unary()?;
                    if d == 0.0 {
                        return Err(bad_weight(at, "division by zero"));
                    }
                    v /= d;
                }
                _ => return Ok(v),
            }
        }
    }

    fn weight_unary(&mut self) -> Result<f64, MlnError> {
        match self.peek() {
            Tok::Minus => {
                self.advance();
                Ok(-self.nested(|p| p.weight_unary())?)
            }
            Tok::Plus => {
                self.advance();
                self.nested(|p| p.weight_unary())
            }
            _ => self.weight_primary(),
        }
    }

    fn weight_primary(&mut self) -> Result<f64, MlnError> {
        let t = self.token().clone();
        match &t.tok {
            Tok::Number(v) => {
                self.advance();
                Ok(*v)
            }
            Tok::LParen => {
                self.advance();
                let v = self.nested(|p| p.weight_sum())?;
                if *self.peek() != Tok::RParen {
                    return Err(self.error("an arithmetic operator (+ - * /) or ')' in the weight"));
                }
                self.advance();
                Ok(v)
            }
            Tok::Ident(f) if FUNCTIONS.contains(&f.as_str()) && *self.peek_at(1) == Tok::LParen => {
                self.advance();
                let x = self.nested(|p| p.weight_primary())?;
                match f.as_str() {
                    "exp" => Ok(libm::exp(x)),
                    _ if x > 0.0 => Ok(libm::log(x)),
                    _ => Err(bad_weight(t.at, &format!("the logarithm of {x} is not defined"))),
                }
            }
            _ => Err(self.error("a number, '(' or log(...) in the weight")),
        }
    }

    /// The statement must end here.
    fn end_of_statement(&mut self, what: &str) -> Result<(), MlnError> {
        if !self.at_line_end() {
            return Err(self.error(what));
        }
        self.advance();
        Ok(())
    }

    fn skip_blank_lines(&mut self) -> bool {
        while *self.peek() == Tok::Newline {
            self.advance();
        }
        *self.peek() != Tok::Eof
    }

    fn statement(&mut self) -> Result<Statement, MlnError> {
        let first = self.token().clone();
        if matches!(first.tok, Tok::Ident(_)) && *self.peek_at(1) == Tok::Eq && *self.peek_at(2) == Tok::LBrace {
            let name = self.name("a type name")?;
            self.advance();
            self.advance();
            let mut constants = Vec::new();
            if *self.peek() != Tok::RBrace {
                loop {
                    let c = self.name("a constant in the domain")?;
                    if c.is_variable() {
                        return Err(MlnError::syntax(
                            c.at,
                            "a constant (starting with a capital letter or a digit)",
                            format!("'{}'", c.text),
                        ));
                    }
                    constants.push(c);
                    match self.peek() {
                        Tok::Comma => {
                            self.advance();
                        }
                        Tok::RBrace => break,
                        _ => return Err(self.error(format!("',' or '}}' in the domain of {}", name.text))),
                    }
                }
            }
            self.advance();
            self.end_of_statement("the end of the line after the domain")?;
            return Ok(Statement::Domain { name, constants });
        }
        let weight = if self.looks_like_weight() {
            let w = self.weight_sum()?;
            if !w.is_finite() {
                return Err(bad_weight(first.at, &format!("{w} is not a finite number")));
            }
            if self.at_line_end() {
                return Err(self.error("a formula after the weight"));
            }
            if !matches!(self.peek(), Tok::Ident(_) | Tok::Not | Tok::LParen | Tok::Number(_)) {
                return Err(self.error("an arithmetic operator (+ - * /) or a formula after the weight"));
            }
            Some(w)
        } else {
            None
        };
        let formula_start = self.token().clone();
        let formula = self.formula()?;
        let last = self.toks[self.i - 1].end;
        let hard = *self.peek() == Tok::Dot;
        if hard {
            if weight.is_some() {
                return Err(
                    self.error("no '.' after a weighted formula (a hard formula ends in '.' and has no weight)")
                );
            }
            self.advance();
        }
        let text = self.src[formula_start.start..last].trim().to_string();
        let expected = if hard {
            "the end of the line after '.'"
        } else {
            "a connective (^ v => <=>), '.' or the end of the line"
        };
        self.end_of_statement(expected)?;
        Ok(Statement::Formula { weight, hard, formula, at: first.at, text })
    }

    fn evidence_line(&mut self) -> Result<EvidenceLine, MlnError> {
        let probability = match self.peek().clone() {
            Tok::Number(p) => {
                let at = self.advance().at;
                if !(p > 0.0 && p < 1.0) {
                    return Err(MlnError::at(super::error::ErrorKind::BadProbability { value: p }, at));
                }
                Some(p)
            }
            _ => None,
        };
        let negated = *self.peek() == Tok::Not;
        if negated {
            self.advance();
        }
        let predicate = match self.peek() {
            Tok::Ident(_) if *self.peek_at(1) == Tok::LParen => self.name("a predicate")?,
            Tok::Ident(s) => {
                let s = s.clone();
                self.advance();
                return Err(self.error(format!("'(' and the arguments of {s}")));
            }
            _ => return Err(self.error("a ground atom such as Pred(A,B), !Pred(A,B) or 0.8 Pred(A)")),
        };
        let args = self.arguments(&predicate.text)?;
        self.end_of_statement("the end of the line after the atom (one atom per line)")?;
        Ok(EvidenceLine { probability, negated, predicate, args })
    }
}

fn bad_weight(at: Position, message: &str) -> MlnError {
    MlnError::at(super::error::ErrorKind::BadWeight { message: message.into() }, at)
}

/// Parses a knowledge base into statements, one per non-blank line.
pub(crate) fn parse_kb(src: &str) -> Result<Vec<Statement>, MlnError> {
    let mut p = Parser::new(src)?;
    let mut out = Vec::new();
    while p.skip_blank_lines() {
        out.push(p.statement()?);
    }
    Ok(out)
}

/// Parses an evidence database, one ground atom per non-blank line.
pub(crate) fn parse_db(src: &str) -> Result<Vec<EvidenceLine>, MlnError> {
    let mut p = Parser::new(src)?;
    let mut out = Vec::new();
    while p.skip_blank_lines() {
        out.push(p.evidence_line()?);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(src: &str) -> String {
        parse_kb(src).unwrap_err().to_string()
    }

    #[test]
    fn weights_and_precedence() {
        let s = parse_kb("// c\n\nlog(0.9/0.1) A(x) ^ !B(x) v C(x) => D(x) <=> E(x)\n").unwrap();
        let Statement::Formula { weight, hard, formula, .. } = &s[0] else { panic!() };
        assert!((weight.unwrap() - 9f64.ln()).abs() < 1e-12);
        assert!(!hard);
        // ((A ^ !B) v C => D) <=> E
        let Raw::Equiv(l, _) = formula else { panic!("{formula:?}") };
        let Raw::Implies(l, _) = &**l else { panic!() };
        let Raw::Or(items) = &**l else { panic!() };
        assert!(matches!(&items[0], Raw::And(a) if a.len() == 2));
    }

    #[test]
    fn arithmetic_weights() {
        for (src, w) in [("-1.5 A(x)", -1.5), ("2*(1+0.5) A(x)", 3.0), ("(1) (A(x))", 1.0), ("1e1 A(x)", 10.0)] {
            let s = parse_kb(src).unwrap();
            let Statement::Formula { weight, .. } = &s[0] else { panic!() };
            assert_eq!(weight.unwrap(), w, "{src}");
        }
        let s = parse_kb("log(x) => A(x).").unwrap();
        assert!(matches!(&s[0], Statement::Formula { weight: None, hard: true, .. }));
    }

    #[test]
    fn positioned_errors() {
        assert_eq!(err("A(x)\n1 A(x ^ B(x)"), "line 2, column 7: expected ')' after the arguments of A, found '^'");
        assert_eq!(
            err("1 (A(x)"),
            "line 1, column 8: expected a connective or ')' to close the '(' at line 1, column 3, found end of input"
        );
        assert_eq!(err("1/0 A(x)"), "line 1, column 2: bad weight: division by zero");
        assert_eq!(err("log(-1) A(x)"), "line 1, column 1: bad weight: the logarithm of -1 is not defined");
        assert_eq!(
            err("1 A(x) B(x)"),
            "line 1, column 8: expected a connective (^ v => <=>), '.' or the end of the line, found 'B'"
        );
        assert_eq!(err("1 A(x) #"), "line 1, column 8: expected a name, a number, a connective (! ^ v => <=>) or a parenthesis (directives such as #include are not supported), found '#'");
        assert_eq!(err("0.5"), "line 1, column 4: expected a formula after the weight, found end of input");
        assert_eq!(err("1 A(x)."), "line 1, column 7: expected no '.' after a weighted formula (a hard formula ends in '.' and has no weight), found '.'");
    }

    #[test]
    fn quantifiers_and_equality() {
        let s = parse_kb("EXIST y,z A(x,y) v x = z.\n1 x != y ^ B(x)").unwrap();
        let Statement::Formula { formula: Raw::Quant { exists: true, vars, body }, .. } = &s[0] else { panic!() };
        assert_eq!(vars.len(), 2);
        assert!(matches!(&**body, Raw::Or(_)));
    }
}
