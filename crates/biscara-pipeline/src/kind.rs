//! What kind of file a program is.

/// The three kinds of program a command can run.
///
/// The first paragraph of each variant's documentation is the help of `--from`'s values (the
/// `clap` feature).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum ProgramKind {
    /// RS274/NGC G-code (LinuxCNC's dialect).
    Gcode,
    /// An inter-file (JSON Lines) written by `biscara interpret`.
    ///
    /// JSON Lines of motions, docs/motion.md.
    Jsonl,
    /// A path CSV written by `biscara interpolate` (joints only).
    ///
    /// Cartesian samples (docs/motion.md): only what computes joints reads it.
    Path,
}

impl ProgramKind {
    /// The kind of a program named `name` whose text starts with `head`: by the extension
    /// (`.jsonl`, `.csv`, anything else is G-code), and for a name without a known extension
    /// (standard input, `job.txt`) by the content: a first non-blank byte `{` is an inter-file,
    /// a first line starting `t_s,` a path CSV. G-code can start with neither.
    pub fn detect(name: &str, head: &[u8]) -> ProgramKind {
        let extension = name.rsplit_once('.').map(|(_, ext)| ext.to_ascii_lowercase());
        match extension.as_deref() {
            Some("jsonl") => return ProgramKind::Jsonl,
            Some("csv") => return ProgramKind::Path,
            Some("ngc" | "nc" | "gcode" | "tap" | "cnc" | "g" | "gc") => {
                return ProgramKind::Gcode;
            }
            _ => {}
        }
        let text = head.trim_ascii_start();
        if text.starts_with(b"{") {
            ProgramKind::Jsonl
        } else if text.starts_with(b"t_s,") {
            ProgramKind::Path
        } else {
            ProgramKind::Gcode
        }
    }

    /// The kind's name in messages.
    pub fn describe(self) -> &'static str {
        match self {
            ProgramKind::Gcode => "G-code",
            ProgramKind::Jsonl => "an inter-file",
            ProgramKind::Path => "a path CSV",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_extension_decides_first() {
        assert_eq!(ProgramKind::detect("a/job.jsonl", b"G0 X1"), ProgramKind::Jsonl);
        assert_eq!(ProgramKind::detect("path.CSV", b""), ProgramKind::Path);
        assert_eq!(ProgramKind::detect("job.ngc", b"{\"line\":1}"), ProgramKind::Gcode);
    }

    #[test]
    fn without_a_known_extension_the_content_decides() {
        assert_eq!(ProgramKind::detect("<stdin>", b"\n  {\"line\":1"), ProgramKind::Jsonl);
        assert_eq!(ProgramKind::detect("<stdin>", b"t_s,x_mm,y_mm"), ProgramKind::Path);
        assert_eq!(ProgramKind::detect("job.txt", b"%\nG0 X0"), ProgramKind::Gcode);
        assert_eq!(ProgramKind::detect("<stdin>", b""), ProgramKind::Gcode);
    }
}
