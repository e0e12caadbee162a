//! How an error reaches the user: one line, the context chain joined, control bytes from input
//! files escaped. The CLI prints it; the window shows the same line in its status bar.

/// The one line `main` prints for an error: `error: ` and the context chain joined by `: `, with
/// any whitespace run inside a message (newlines included) folded to a space so that the report
/// stays on one line, and every other control character (escape sequences, backspace, bidi
/// overrides) written as a `\u{..}` escape. Error messages quote names and tokens taken from
/// input files; this keeps such bytes from reaching the terminal raw.
pub fn error_line(error: &anyhow::Error) -> String {
    let text = format!("{error:#}");
    let mut line = String::from("error:");
    for word in text.split_whitespace() {
        line.push(' ');
        for c in word.chars() {
            if is_terminal_control(c) {
                line.extend(c.escape_unicode());
            } else {
                line.push(c);
            }
        }
    }
    line
}

/// Characters a terminal may act on rather than show: C0/C1 controls, DEL, and the Unicode
/// direction overrides and isolates (which reorder what follows them on the line).
fn is_terminal_control(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{200e}' | '\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

#[cfg(test)]
mod tests {
    #[test]
    fn error_line_is_one_line_without_raw_control_bytes() {
        let error = anyhow::anyhow!("object 'evil\u{1b}[31mred\u{7}' is bad\nnext\u{202e}line")
            .context("knee\r\n.obj");
        let line = super::error_line(&error);
        assert_eq!(
            line,
            "error: knee .obj: object 'evil\\u{1b}[31mred\\u{7}' is bad next\\u{202e}line"
        );
        assert!(!line.chars().any(super::is_terminal_control));
    }
}
