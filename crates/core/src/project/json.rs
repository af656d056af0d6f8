//! JSON plumbing of the project file: the shape check against the default project, and
//! path edits (the strict parse is `crate::base::json`).

use serde_json::Value;

pub(crate) use crate::base::json::{join, parse_strict};

/// A short name of a JSON value's type, for messages.
pub(crate) fn type_name(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

/// Every field of `value` that `schema` (the default project as JSON) does not have, and
/// every place where an object is expected but something else is given.
pub(crate) fn check_shape(value: &Value, schema: &Value, at: &str, out: &mut Vec<String>) {
    let Value::Object(s) = schema else { return };
    let Value::Object(v) = value else {
        let what = if at.is_empty() {
            "the project".to_owned()
        } else {
            format!("`{at}`")
        };
        out.push(format!(
            "{what}: expected an object {{ … }}, found {}",
            type_name(value)
        ));
        return;
    };
    for (key, child) in v {
        let path = join(at, key);
        match s.get(key) {
            None => {
                let known: Vec<&str> = s.keys().map(String::as_str).collect();
                out.push(format!(
                    "unknown field `{}`; expected one of: {}",
                    crate::base::limits::shorten(&path, 80),
                    known.join(", ")
                ));
            }
            Some(sub) => check_shape(child, sub, &path, out),
        }
    }
}

/// The value at a dotted path, if present.
pub(crate) fn get_path<'v>(value: &'v Value, path: &str) -> Option<&'v Value> {
    path.split('.').try_fold(value, |node, key| node.get(key))
}

/// Replaces the value at a dotted path (which must exist).
pub(crate) fn set_path(doc: &mut Value, path: &str, value: Value) -> Result<(), String> {
    let mut node = doc;
    for key in path.split('.') {
        node = node
            .get_mut(key)
            .ok_or_else(|| format!("unknown field `{path}`"))?;
    }
    *node = value;
    Ok(())
}
