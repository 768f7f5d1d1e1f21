//! The field of a scene at a position of its JSON text. serde's messages for a value of the
//! wrong type or a malformed one (`invalid type: floating point `2.0`, expected u32 at line 1
//! column 211`) give a line and a column but not the field; for a scene built in Python from a
//! dict the line and column are those of a text the user never saw. [`parse`] puts the field's
//! path (`impacts`, `blocks[1].mass`, `excitation`) in front of such a message.

use super::{SceneError, SceneSpec};

/// Parses the JSON text of a scene; an error names the field it is in (a top-level one reads
/// as before: `unknown field `frition`, expected one of …`).
pub fn parse(text: &str) -> Result<SceneSpec, SceneError> {
    if let Ok(value) = serde_json::from_str::<serde_json::Value>(text) {
        objects_where_expected(&value)?;
    }
    serde_json::from_str(text).map_err(|e| SceneError(with_field(text, &e)))
}

/// serde reads a struct from a list as well, by position: `"blocks": [[1, 2, 5000]]` was a
/// block of width 1, height 2 and mass 5000, `"integrator": ["wilson", 1.4]` a θ. Where the
/// scene has an object, a list is refused, named.
fn objects_where_expected(scene: &serde_json::Value) -> Result<(), SceneError> {
    use serde_json::Value;
    let list = |path: &str| {
        SceneError(format!(
            "{path}: a list where an object with named fields is expected (values are not read \
             by position)"
        ))
    };
    let Some(fields) = scene.as_object() else {
        return match scene {
            Value::Array(_) => Err(list("scene")),
            _ => Ok(()), // serde says what it is
        };
    };
    if let Some(Value::Array(blocks)) = fields.get("blocks") {
        if let Some(k) = blocks.iter().position(Value::is_array) {
            return Err(list(&format!("blocks[{k}]")));
        }
    }
    for key in ["arch", "colonnade", "excitation", "integrator", "output"] {
        if fields.get(key).is_some_and(Value::is_array) {
            return Err(list(key));
        }
    }
    Ok(())
}

/// serde's message, after the path of the field at its position when there is one.
fn with_field(text: &str, e: &serde_json::Error) -> String {
    use serde_json::error::Category;
    let message = e.to_string();
    if !matches!(e.classify(), Category::Data | Category::Syntax) {
        return message;
    }
    // An unknown field is named by the message: the object it is in is the news, the last
    // object before the position with that key (serde reads some values whole — an internally
    // tagged `excitation`, an untagged `integrator` — and places their errors after them, or
    // after the object they end).
    let unknown = message
        .strip_prefix("unknown field `")
        .and_then(|m| m.split_once('`'))
        .map(|(key, _)| key);
    let end = offset(text, e.line(), e.column());
    let (mut path, closed, owner) = field_at(text, end, unknown);
    if let Some(owner) = owner {
        path = owner;
    } else if !closed && message.starts_with("duplicate field") {
        // A repeated key, read as such: the object it is in.
        path.pop();
    } else if closed && path.is_empty() && end > 0 && missing_below_top(text, &message) {
        // A field missing in a value serde reads whole (an internally tagged `excitation`),
        // last in the scene: its error comes after the scene's end, where the value closed
        // just before the scene's closing brace is the one.
        let (inner, inner_closed, _) = field_at(text, end - 1, None);
        if inner_closed {
            path = inner;
        }
    }
    let path = render(&path);
    if path.is_empty() || message.starts_with(&format!("{path}:")) {
        message
    } else {
        format!("{path}: {message}")
    }
}

/// `message` says a field is missing which the scene itself has: it is missing in one of the
/// scene's values, not in the scene.
fn missing_below_top(text: &str, message: &str) -> bool {
    let Some((key, _)) = message
        .strip_prefix("missing field `")
        .and_then(|m| m.split_once('`'))
    else {
        return false;
    };
    serde_json::from_str::<serde_json::Value>(text)
        .ok()
        .is_some_and(|scene| scene.get(key).is_some())
}

/// One step of a path: an object's key or an array's index.
#[derive(Debug)]
enum Step {
    Key(String),
    Index(usize),
}

fn render(path: &[Step]) -> String {
    let mut s = String::new();
    for step in path {
        match step {
            Step::Key(k) if s.is_empty() => s.push_str(k),
            Step::Key(k) => {
                s.push('.');
                s.push_str(k);
            }
            Step::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

/// An open object (its current key, whether its colon was read) or array (its index).
enum Frame {
    Object(Option<String>, bool),
    Array(usize),
}

fn steps(frames: &[Frame]) -> Vec<Step> {
    frames
        .iter()
        .filter_map(|f| match f {
            Frame::Object(Some(k), _) => Some(Step::Key(k.clone())),
            Frame::Object(None, _) => None,
            Frame::Array(i) => Some(Step::Index(*i)),
        })
        .collect()
}

/// The byte offset of serde_json's `line`, `column` (1-based, in bytes) in `text`, clamped to it.
fn offset(text: &str, line: usize, column: usize) -> usize {
    let mut start = 0;
    for _ in 1..line {
        match text[start..].find('\n') {
            Some(i) => start += i + 1,
            None => break,
        }
    }
    (start + column).min(text.len())
}

/// The path of the value being read when the first `end` bytes of `text` had been read: the keys and indices of the objects and arrays open there; or, when
/// an object or array had just closed there (`true`), that value's path. Third: the path of the
/// last object before the position with the key `unknown`.
fn field_at(text: &str, end: usize, unknown: Option<&str>) -> (Vec<Step>, bool, Option<Vec<Step>>) {
    let mut stack: Vec<Frame> = Vec::new();
    let mut closed: Option<Vec<Step>> = None;
    let mut owner = None;
    let mut bytes = text.as_bytes()[..end].iter().enumerate();
    while let Some((i, &b)) = bytes.next() {
        if !b.is_ascii_whitespace() {
            closed = None;
        }
        match b {
            b'{' => stack.push(Frame::Object(None, false)),
            b'[' => stack.push(Frame::Array(0)),
            b'}' | b']' => {
                let depth = stack.len().saturating_sub(1);
                closed = Some(steps(&stack[..depth]));
                stack.truncate(depth);
            }
            b':' => {
                if let Some(Frame::Object(_, colon)) = stack.last_mut() {
                    *colon = true;
                }
            }
            b',' => match stack.last_mut() {
                Some(Frame::Object(key, colon)) => {
                    *key = None;
                    *colon = false;
                }
                Some(Frame::Array(index)) => *index += 1,
                None => {}
            },
            b'"' => {
                // A string: to its closing quote (escapes skipped), or to the position.
                let mut quote = end;
                while let Some((j, &c)) = bytes.next() {
                    if c == b'\\' {
                        bytes.next();
                    } else if c == b'"' {
                        quote = j;
                        break;
                    }
                }
                if let Some(Frame::Object(None, false)) = stack.last() {
                    let raw = String::from_utf8_lossy(&text.as_bytes()[i + 1..quote]);
                    if unknown == Some(&*raw) {
                        owner = Some(steps(&stack));
                    }
                    stack.pop();
                    stack.push(Frame::Object(Some(raw.into_owned()), false));
                }
            }
            _ => {}
        }
    }
    match closed {
        Some(path) => (path, true, owner),
        None => (steps(&stack), false, owner),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error(text: &str) -> String {
        parse(text).expect_err("accepted").0
    }

    #[test]
    fn the_field_of_a_bad_value_is_named() {
        let base = r#""excitation": {"type": "none"}, "duration": 1, "dt": 0.001"#;
        let block = r#"{"width": 1, "height": 2, "mass": 5000}"#;
        let mut bad = Vec::new();
        for (text, path) in [
            (
                format!(r#"{{"blocks": [{block}], {base}, "impacts": 2.0}}"#),
                "impacts: invalid type",
            ),
            (
                format!(
                    r#"{{"blocks": [{block}, {{"width": 1, "height": "2", "mass": 1}}], {base}}}"#
                ),
                "blocks[1].height: invalid type",
            ),
            (
                format!(
                    r#"{{"blocks": [{block}], {base}, "integrator": {{"type": "wilson", "theta": 1.4, "gamma": 1}}}}"#
                ),
                "integrator: ",
            ),
            (
                format!(
                    r#"{{"blocks": [{block}], "excitation": {{"type": "half_sine", "amplitude": NaN, "duration": 1}}, "duration": 1, "dt": 0.001}}"#
                ),
                "excitation.amplitude: expected value",
            ),
            (
                format!(
                    r#"{{"blocks": [{block}], "excitation": {{"type": "half_sine", "amplitude": 1, "phase": 1, "duration": 1}}, "duration": 1, "dt": 0.001}}"#
                ),
                "excitation: unknown field `phase`",
            ),
            (
                format!(
                    r#"{{"blocks": [{block}], "excitation": {{"type": "half_sine", "amplitude": 1}}, "duration": 1, "dt": 0.001}}"#
                ),
                "excitation: missing field `duration`",
            ),
            (
                format!(
                    r#"{{"arch": {{"radius": 5, "thickness": 0.75, "voussoirs": 8.5}}, {base}}}"#
                ),
                "arch.voussoirs: invalid type",
            ),
            (
                format!("{{\"blocks\": [{block}],\n {base},\n \"output\": {{\"every\": -1}}}}"),
                "output.every: invalid value",
            ),
        ] {
            let e = error(&text);
            if !e.starts_with(path) {
                bad.push(format!("{path} | {e}"));
            }
        }
        assert!(bad.is_empty(), "{bad:#?}");
        // A value serde reads whole, last in the scene: its error comes after the scene's end.
        let e = error(&format!(
            r#"{{"blocks": [{block}], "duration": 1, "dt": 0.001, "excitation": {{"type": "none", "phase": 1}}}}"#
        ));
        assert!(e.starts_with("excitation: unknown field `phase`"), "{e}");
        // And a field missing there, which the scene has under the same name: the excitation's.
        for space in ["", " ", "\n"] {
            let e = error(&format!(
                r#"{{"blocks": [{block}], "duration": 1, "dt": 0.001, "excitation": {{"type": "half_sine", "amplitude": 1}}{space}}}"#
            ));
            assert!(e.starts_with("excitation: missing field `duration`"), "{e}");
        }
        // Lists where the scene has objects: refused, not read by position.
        for (text, path) in [
            (
                format!(r#"{{"blocks": [{block}, [1, 2, 5000]], {base}}}"#),
                "blocks[1]: a list",
            ),
            (
                format!(r#"{{"blocks": [{block}], {base}, "integrator": ["wilson", 1.4]}}"#),
                "integrator: a list",
            ),
            (
                format!(r#"{{"arch": [5, 0.75, 180, 8], {base}}}"#),
                "arch: a list",
            ),
            ("[]".to_string(), "scene: a list"),
        ] {
            let e = error(&text);
            assert!(e.starts_with(path), "{path}: {e}");
        }
        // Top-level fields read as serde says them, without a path in front.
        let e = error(&format!(
            r#"{{"blocks": [{block}], {base}, "frition": 0.5}}"#
        ));
        assert!(e.starts_with("unknown field `frition`"), "{e}");
        let e = error(&format!(
            r#"{{"blocks": [{block}], "duration": 1, "dt": 0.001}}"#
        ));
        assert!(e.starts_with("missing field `excitation`"), "{e}");
        // A key with an escaped quote and a bracket in a string do not lose the path.
        let e = error(&format!(
            r#"{{"title": "a \"[{{\" title", "blocks": [{block}], {base}, "gravity": "high"}}"#
        ));
        assert!(e.starts_with("gravity: invalid type"), "{e}");
    }
}
