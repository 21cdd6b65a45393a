//! A robot as text: what `Robot.description()` returns and
//! `Robot.from_description` reads, so that a robot crosses processes (pickle,
//! Dask workers) as the text it was built from, never as a Rust object.
//!
//! The text is one of the library's robot sources:
//! - a built-in robot's name (`"ur5"`; `armkit::robots::by_name`);
//! - URDF text (it starts with `<`), optionally led by a comment naming the
//!   chain, `<!-- armkit chain base="world" tip="tool0" -->`, when the chain
//!   is not the default one (root to the only leaf);
//! - a DH description in JSON (it starts with `{`) or TOML (anything else),
//!   the format of `armkit::description`.

use armkit::description::{parse_str, Format};
use armkit::urdf::ChainSelection;
use armkit::{Error, Model, Result};

/// The leading comment of a URDF description that names its chain.
const CHAIN_COMMENT: &str = "<!-- armkit chain";

/// Where a robot's model came from, kept to give its description.
#[derive(Clone, Debug)]
pub(crate) enum Source {
    /// A built-in robot, by the name it was asked for.
    Builtin(String),
    /// URDF text and the chain taken from it.
    Urdf {
        text: String,
        selection: ChainSelection,
    },
    /// A DH description (TOML or JSON text).
    Dh(String),
}

impl Source {
    /// The description text (see the module docs).
    pub(crate) fn text(&self) -> String {
        match self {
            Source::Builtin(name) => name.clone(),
            Source::Dh(text) => text.clone(),
            Source::Urdf { text, selection } => {
                let mut attributes = String::new();
                for (key, value) in [("base", &selection.base), ("tip", &selection.tip)] {
                    if let Some(value) = value {
                        attributes.push_str(&format!(" {key}=\"{}\"", escape(value)));
                    }
                }
                if attributes.is_empty() {
                    text.clone()
                } else {
                    format!("{CHAIN_COMMENT}{attributes} -->\n{text}")
                }
            }
        }
    }

    /// Builds the model a description names. Errors: an unknown built-in
    /// name, or the URDF or DH parser's error (`source_name` names the text).
    pub(crate) fn parse(text: &str, source_name: &str) -> Result<(Model, Source)> {
        let trimmed = text.trim();
        if trimmed.is_empty() {
            return Err(Error::invalid_argument(
                "description",
                "the text is empty (expected a built-in robot's name, URDF text or a DH description)",
            ));
        }
        if trimmed.starts_with('<') {
            let (selection, urdf) = split_chain_comment(text.trim_start())
                .map_err(|reason| Error::invalid_argument("description", reason))?;
            let model = armkit::urdf::parse_str(urdf, source_name, &selection)?;
            let source = Source::Urdf {
                text: urdf.to_string(),
                selection,
            };
            return Ok((model, source));
        }
        if trimmed.starts_with('{') {
            let model = parse_str(text, Format::Json, source_name)?;
            return Ok((model, Source::Dh(text.to_string())));
        }
        if !trimmed.contains(char::is_whitespace) && !trimmed.contains('=') {
            let model = armkit::robots::by_name(trimmed)?;
            return Ok((model, Source::Builtin(trimmed.to_string())));
        }
        let model = parse_str(text, Format::Toml, source_name)?;
        Ok((model, Source::Dh(text.to_string())))
    }
}

/// The chain named by a leading `<!-- armkit chain ... -->` comment (the
/// default chain without one) and the URDF text after it.
fn split_chain_comment(text: &str) -> std::result::Result<(ChainSelection, &str), String> {
    let Some(rest) = text.strip_prefix(CHAIN_COMMENT) else {
        return Ok((ChainSelection::default(), text));
    };
    let end = rest
        .find("-->")
        .ok_or("the `<!-- armkit chain` comment is not closed by `-->`")?;
    let mut selection = ChainSelection::default();
    let mut attributes = rest[..end].trim();
    while !attributes.is_empty() {
        let (key, after) = attributes
            .split_once("=\"")
            .ok_or_else(|| format!("the chain comment's `{attributes}` is not key=\"value\""))?;
        let (value, after) = after
            .split_once('"')
            .ok_or_else(|| format!("the chain comment's {key} value is not closed by `\"`"))?;
        let value = Some(unescape(value));
        match key.trim() {
            "base" => selection.base = value,
            "tip" => selection.tip = value,
            other => {
                return Err(format!(
                    "the chain comment names `{other}` (expected base and tip)"
                ))
            }
        }
        attributes = after.trim_start();
    }
    Ok((selection, rest[end + 3..].trim_start()))
}

/// A link name as an attribute value: `&`, `"`, `<`, `>` as XML entities.
fn escape(value: &str) -> String {
    value
        .replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The inverse of [`escape`].
fn unescape(value: &str) -> String {
    value
        .replace("&quot;", "\"")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&")
}
