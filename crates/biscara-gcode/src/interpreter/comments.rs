//! Comments LinuxCNC executes: `(ABORT, …)`, and Python's `(py,…)`, `(pyrun,…)`,
//! `(pyreload)`.

use super::*;

/// Where the last `( … )` comment before any `;` of `line` is: its `(`, its text (after the
/// blanks that follow the `(`) and its `)`.
pub(super) fn last_comment(line: &[u8]) -> Option<(usize, usize, usize)> {
    let mut last = None;
    let mut at = 0;
    while let Some(open) = line[at..].iter().position(|&b| b == b'(').map(|i| at + i) {
        if line[at..open].contains(&b';') {
            break;
        }
        let Some(close) = line[open..].iter().position(|&b| b == b')').map(|i| open + i) else {
            break;
        };
        last = Some((open, close));
        at = close + 1;
    }
    let (open, close) = last?;
    let blanks = line[open + 1..close].iter().take_while(|b| b.is_ascii_whitespace()).count();
    Some((open, open + 1 + blanks, close))
}

impl Machine {
    /// LinuxCNC's `(ABORT, text)`: `line`'s last comment, when it reads `abort,` (spaces
    /// before it allowed, any case), stops the program with its text as the message, `#n` and
    /// `#<name>` in it replaced by their values (`######` when undefined).
    pub(super) fn abort_comment(&self, line: &[u8]) -> Result<(), Fault> {
        let Some((open, text, close)) = last_comment(line) else { return Ok(()) };
        let text = &line[text..close];
        if !text.get(..6).is_some_and(|head| head.eq_ignore_ascii_case(b"abort,")) {
            return Ok(());
        }
        let text = &text[6..];
        let mut message = String::new();
        let mut index = 0;
        while index < text.len() {
            if text[index] != b'#' {
                let run =
                    text[index..].iter().position(|&b| b == b'#').unwrap_or(text.len() - index);
                message.push_str(&String::from_utf8_lossy(&text[index..index + run]));
                index += run;
                continue;
            }
            let rest = &text[index + 1..];
            if rest.first() == Some(&b'<')
                && let Some(end) = rest.iter().position(|&b| b == b'>')
            {
                let name: Vec<u8> = rest[1..end]
                    .iter()
                    .filter(|b| !b.is_ascii_whitespace())
                    .map(u8::to_ascii_lowercase)
                    .collect();
                let value = if name.first() == Some(&b'_') {
                    self.state.predefined(&name).or_else(|| self.state.params.named(&name))
                } else {
                    self.state.params.named(&name)
                };
                match value {
                    Some(value) => message.push_str(&format!("{value:.6}")),
                    None => message.push_str("######"),
                }
                index += end + 2;
                continue;
            }
            let digits = rest.iter().take_while(|b| b.is_ascii_digit()).count();
            let number = std::str::from_utf8(&rest[..digits]).ok().and_then(|d| d.parse().ok());
            match number
                .filter(|&n: &usize| (1..crate::syntax::params::MAX_PARAMETERS).contains(&n))
            {
                Some(number) => message.push_str(&format!("{:.6}", self.state.params.get(number))),
                None if digits == 0 => message.push('#'),
                None => message.push_str("######"),
            }
            index += 1 + digits;
        }
        if message.is_empty() {
            message.push_str("Unknown error, bad error code");
        }
        let (first, last) = (open, close + 1);
        Err(Fault::invalid(first, last, message))
    }
}

/// What a comment asks of Python (LinuxCNC's `convert_comment`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum PythonComment {
    /// `py,CODE` (and a `;py,CODE` line).
    Run,
    /// `pyrun,FILE`: the file's code.
    RunFile,
    /// `pyreload`: `TOPLEVEL` again.
    Reload,
}

impl PythonComment {
    /// The action a comment's text (blanks before it skipped) asks for, and the text it acts on.
    pub(super) fn of(text: &[u8]) -> Option<(PythonComment, &[u8])> {
        let starts = |prefix: &[u8]| {
            text.get(..prefix.len()).is_some_and(|head| head.eq_ignore_ascii_case(prefix))
        };
        if starts(b"py,") {
            Some((PythonComment::Run, &text[3..]))
        } else if starts(b"pyrun,") {
            Some((PythonComment::RunFile, &text[6..]))
        } else if starts(b"pyreload") {
            Some((PythonComment::Reload, &[]))
        } else {
            None
        }
    }
}
