//! A small XML well-formedness scanner that runs before `urdf-rs`.
//!
//! Why: `urdf-rs` reports malformed XML and missing fields without a line or
//! the element concerned ("Elements not properly nested", "missing field
//! `parent`"). This scanner checks nesting, tags, attributes, comments and
//! processing instructions, says where the first problem is (line, column and
//! the element), and records where each top-level element of the root starts
//! and ends so that a later `urdf-rs` error can be traced to the `<link>` or
//! `<joint>` it comes from. It builds no tree and decodes no entities: it only
//! scans.

use std::ops::Range;

/// One child element of the root (a `<link>`, `<joint>`, `<material>`, ...).
#[derive(Clone, Debug)]
pub(super) struct TopElement {
    /// Tag name.
    pub name: String,
    /// Value of its `name` attribute, if any.
    pub name_attribute: Option<String>,
    /// 1-based line of its start tag.
    pub line: usize,
    /// Byte range of the whole element, start tag to end tag.
    pub span: Range<usize>,
    /// Its own child elements: tag name and byte range, in document order.
    pub children: Vec<(String, Range<usize>)>,
}

/// What the scan found in a well-formed document.
#[derive(Clone, Debug)]
pub(super) struct Document {
    /// Tag name of the root element.
    pub root: String,
    /// Byte range of the root's start tag.
    pub root_start_tag: Range<usize>,
    /// The root's child elements, in document order.
    pub children: Vec<TopElement>,
}

/// An element whose end tag has not been seen yet.
struct OpenElement {
    name: String,
    name_attribute: Option<String>,
    start: usize,
}

impl OpenElement {
    fn describe(&self, text: &str) -> String {
        let line = line_and_column(text, self.start).0;
        match &self.name_attribute {
            Some(n) => format!("<{} name=\"{n}\"> opened at line {line}", self.name),
            None => format!("<{}> opened at line {line}", self.name),
        }
    }
}

/// 1-based line and column (in characters) of a byte offset.
pub(super) fn line_and_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |p| p + 1);
    (line, before[line_start..].chars().count() + 1)
}

fn error_at(text: &str, offset: usize, message: impl AsRef<str>) -> String {
    let (line, column) = line_and_column(text, offset);
    format!(
        "malformed XML at line {line}, column {column}: {}",
        message.as_ref()
    )
}

fn is_name_byte(b: u8) -> bool {
    !(b.is_ascii_whitespace() || matches!(b, b'<' | b'>' | b'/' | b'=' | b'"' | b'\''))
}

fn skip_whitespace(bytes: &[u8], mut i: usize) -> usize {
    while i < bytes.len() && bytes[i].is_ascii_whitespace() {
        i += 1;
    }
    i
}

fn read_name(text: &str, start: usize) -> (&str, usize) {
    let bytes = text.as_bytes();
    let mut end = start;
    while end < bytes.len() && is_name_byte(bytes[end]) {
        end += 1;
    }
    (&text[start..end], end)
}

/// Offset just past the first `terminator` at or after `from`, or an error
/// naming the unterminated construct that started at `start`.
fn skip_past(
    text: &str,
    start: usize,
    from: usize,
    terminator: &str,
    what: &str,
) -> Result<usize, String> {
    text[from..]
        .find(terminator)
        .map(|p| from + p + terminator.len())
        .ok_or_else(|| {
            error_at(
                text,
                start,
                format!("{what} is never closed by `{terminator}`"),
            )
        })
}

/// Skips `<!DOCTYPE ...>`, including an internal subset in brackets.
fn skip_declaration(text: &str, start: usize) -> Result<usize, String> {
    let bytes = text.as_bytes();
    let mut depth = 0usize;
    let mut i = start + 2;
    while i < bytes.len() {
        match bytes[i] {
            b'[' => depth += 1,
            b']' => depth = depth.saturating_sub(1),
            b'>' if depth == 0 => return Ok(i + 1),
            _ => {}
        }
        i += 1;
    }
    Err(error_at(text, start, "`<!` declaration is never closed"))
}

/// A start tag: its name, `name` attribute, end offset and whether it closes itself.
struct StartTag<'t> {
    name: &'t str,
    name_attribute: Option<String>,
    end: usize,
    self_closing: bool,
}

fn read_start_tag(text: &str, start: usize) -> Result<StartTag<'_>, String> {
    let bytes = text.as_bytes();
    let (name, mut i) = read_name(text, start + 1);
    if name.is_empty() {
        return Err(error_at(
            text,
            start,
            "`<` is not followed by an element name",
        ));
    }
    let mut name_attribute = None;
    let mut seen: Vec<&str> = Vec::new();
    loop {
        let after_space = skip_whitespace(bytes, i);
        if after_space >= bytes.len() {
            return Err(error_at(
                text,
                start,
                format!("the <{name}> tag is never closed by `>`"),
            ));
        }
        if bytes[after_space] == b'>' {
            return Ok(StartTag {
                name,
                name_attribute,
                end: after_space + 1,
                self_closing: false,
            });
        }
        if text[after_space..].starts_with("/>") {
            return Ok(StartTag {
                name,
                name_attribute,
                end: after_space + 2,
                self_closing: true,
            });
        }
        let (attribute, after_attribute) = read_name(text, after_space);
        if attribute.is_empty() || after_space == i {
            let shown = text[after_space..].chars().next().unwrap_or(' ');
            return Err(error_at(
                text,
                after_space,
                format!("unexpected `{shown}` in the <{name}> tag"),
            ));
        }
        if seen.contains(&attribute) {
            return Err(error_at(
                text,
                after_space,
                format!("attribute `{attribute}` appears twice in the <{name}> tag"),
            ));
        }
        seen.push(attribute);
        let equals = skip_whitespace(bytes, after_attribute);
        if equals >= bytes.len() || bytes[equals] != b'=' {
            return Err(error_at(
                text,
                after_space,
                format!("attribute `{attribute}` of <{name}> has no `=\"value\"`"),
            ));
        }
        let quote_at = skip_whitespace(bytes, equals + 1);
        let quote = bytes.get(quote_at).copied();
        if !matches!(quote, Some(b'"') | Some(b'\'')) {
            return Err(error_at(
                text,
                quote_at,
                format!("the value of attribute `{attribute}` of <{name}> is not quoted"),
            ));
        }
        let quote_char = if quote == Some(b'"') { "\"" } else { "'" };
        let value_start = quote_at + 1;
        let value_end = text[value_start..]
            .find(quote_char)
            .map(|p| value_start + p)
            .ok_or_else(|| {
                error_at(
                    text,
                    quote_at,
                    format!("the value of attribute `{attribute}` of <{name}> is never closed"),
                )
            })?;
        if attribute == "name" {
            name_attribute = Some(text[value_start..value_end].to_string());
        }
        i = value_end + 1;
    }
}

/// Scans `text`; returns the root's name and its top-level children, or a
/// message `malformed XML at line L, column C: ...` naming the element.
pub(super) fn scan(text: &str) -> Result<Document, String> {
    let bytes = text.as_bytes();
    let mut stack: Vec<OpenElement> = Vec::new();
    let mut root: Option<(String, Range<usize>)> = None;
    let mut root_closed = false;
    let mut children = Vec::new();
    // Children of the top-level element being read.
    let mut grandchildren = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] != b'<' {
            let next = text[i..].find('<').map_or(bytes.len(), |p| i + p);
            if stack.is_empty() {
                if let Some(offset) = text[i..next].find(|c: char| !c.is_whitespace()) {
                    let where_ = if root_closed { "after" } else { "before" };
                    return Err(error_at(
                        text,
                        i + offset,
                        format!("text {where_} the root element"),
                    ));
                }
            }
            i = next;
            continue;
        }
        let rest = &text[i..];
        if rest.starts_with("<?") {
            i = skip_past(text, i, i + 2, "?>", "the processing instruction `<?`")?;
        } else if rest.starts_with("<!--") {
            i = skip_past(text, i, i + 4, "-->", "the comment `<!--`")?;
        } else if rest.starts_with("<![CDATA[") {
            if stack.is_empty() {
                return Err(error_at(text, i, "CDATA section outside the root element"));
            }
            i = skip_past(text, i, i + 9, "]]>", "the CDATA section")?;
        } else if rest.starts_with("<!") {
            i = skip_declaration(text, i)?;
        } else if rest.starts_with("</") {
            let (name, after_name) = read_name(text, i + 2);
            let close = skip_whitespace(bytes, after_name);
            if bytes.get(close) != Some(&b'>') {
                return Err(error_at(
                    text,
                    i,
                    format!("the end tag `</{name}` is never closed by `>`"),
                ));
            }
            let Some(open) = stack.pop() else {
                return Err(error_at(
                    text,
                    i,
                    format!("end tag `</{name}>` without a start tag"),
                ));
            };
            if open.name != name {
                return Err(error_at(
                    text,
                    i,
                    format!("`</{name}>` closes {}", open.describe(text)),
                ));
            }
            let end = close + 1;
            if stack.len() == 2 {
                grandchildren.push((open.name, open.start..end));
            } else if stack.len() == 1 {
                children.push(top_element(
                    text,
                    open,
                    end,
                    std::mem::take(&mut grandchildren),
                ));
            } else if stack.is_empty() {
                root_closed = true;
            }
            i = end;
        } else {
            let tag = read_start_tag(text, i)?;
            if root_closed {
                return Err(error_at(
                    text,
                    i,
                    format!("a second root element <{}> after the first one", tag.name),
                ));
            }
            if stack.is_empty() {
                root = Some((tag.name.to_string(), i..tag.end));
            }
            let open = OpenElement {
                name: tag.name.to_string(),
                name_attribute: tag.name_attribute,
                start: i,
            };
            if !tag.self_closing {
                stack.push(open);
            } else if stack.len() == 2 {
                grandchildren.push((open.name, open.start..tag.end));
            } else if stack.len() == 1 {
                children.push(top_element(text, open, tag.end, Vec::new()));
            } else if stack.is_empty() {
                root_closed = true;
            }
            i = tag.end;
        }
    }
    if let Some(open) = stack.last() {
        return Err(error_at(
            text,
            bytes.len(),
            format!("{} is never closed", open.describe(text)),
        ));
    }
    let Some((root, root_start_tag)) = root else {
        return Err(error_at(
            text,
            bytes.len(),
            "no root element (the text holds no XML element)",
        ));
    };
    Ok(Document {
        root,
        root_start_tag,
        children,
    })
}

fn top_element(
    text: &str,
    open: OpenElement,
    end: usize,
    children: Vec<(String, Range<usize>)>,
) -> TopElement {
    TopElement {
        line: line_and_column(text, open.start).0,
        name: open.name,
        name_attribute: open.name_attribute,
        span: open.start..end,
        children,
    }
}

/// The elements a chain's kinematics and mass properties read: `<link>`
/// (its `<inertial>`) and `<joint>` (`origin`, `parent`, `child`, `axis`,
/// `limit`, `mimic`). Everything else (visual, collision, material,
/// texture, transmission, gazebo, sensor, calibration, dynamics,
/// safety_controller, vendor extensions) is blanked before `urdf-rs` parses
/// the text, so that however it is written it cannot block a load.
fn is_read(top: &str, child: Option<&str>) -> bool {
    match (top, child) {
        ("link" | "joint", None) => true,
        ("link", Some(child)) => child == "inertial",
        ("joint", Some(child)) => matches!(
            child,
            "origin" | "parent" | "child" | "axis" | "limit" | "mimic"
        ),
        _ => false,
    }
}

/// `text` with every element [`is_read`] rejects replaced by spaces
/// (newlines kept), so byte offsets and line numbers stay those of `text`.
pub(super) fn kinematic_text(text: &str, document: &Document) -> String {
    let mut bytes = text.as_bytes().to_vec();
    let mut blank = |range: &Range<usize>| {
        for b in &mut bytes[range.clone()] {
            if *b != b'\n' {
                *b = b' ';
            }
        }
    };
    for element in &document.children {
        if !is_read(&element.name, None) {
            blank(&element.span);
            continue;
        }
        for (name, span) in &element.children {
            if !is_read(&element.name, Some(name)) {
                blank(span);
            }
        }
    }
    // Only whole elements (from `<` to `>`, ASCII) were blanked, with ASCII
    // spaces: the text is still UTF-8.
    String::from_utf8(bytes).unwrap_or_else(|_| text.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_top_level_children_with_lines() {
        let text = "<?xml version='1.0'?>\n<!-- c -->\n<robot name=\"r\">\n  <link name=\"a\"/>\n  <joint name='j' type=\"fixed\">\n    <parent link=\"a\"/>\n  </joint>\n</robot>\n";
        let doc = scan(text).unwrap();
        assert_eq!(doc.root, "robot");
        assert_eq!(doc.children.len(), 2);
        assert_eq!(doc.children[0].name, "link");
        assert_eq!(doc.children[0].line, 4);
        assert_eq!(doc.children[1].name_attribute.as_deref(), Some("j"));
        assert_eq!(doc.children[1].line, 5);
        assert!(text[doc.children[1].span.clone()].ends_with("</joint>"));
        assert_eq!(&text[doc.root_start_tag.clone()], "<robot name=\"r\">");
    }

    #[test]
    fn kinematic_text_blanks_what_the_model_does_not_read() {
        let text = "<robot name=\"r\">\n<material name=\"m\"><texture/></material>\n<link name=\"a\">\n  <visual><geometry><mesh/></geometry><material name=\"x\"><texture /></material></visual>\n  <inertial><mass value=\"1\"/></inertial>\n</link>\n<joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/><calibration rising=\"x\"/><safety_controller/></joint>\n<gazebo><sensor/></gazebo>\n</robot>\n";
        let doc = scan(text).unwrap();
        let kept = kinematic_text(text, &doc);
        assert_eq!(kept.len(), text.len());
        assert_eq!(kept.lines().count(), text.lines().count());
        for gone in [
            "material",
            "texture",
            "visual",
            "gazebo",
            "sensor",
            "calibration",
            "safety_controller",
        ] {
            assert!(!kept.contains(gone), "{gone}: {kept}");
        }
        for stays in [
            "<inertial><mass value=\"1\"/></inertial>",
            "<parent link=\"a\"/>",
            "<child link=\"b\"/>",
            "<link name=\"a\">",
            "<joint name=\"j\"",
        ] {
            assert!(kept.contains(stays), "{stays}: {kept}");
        }
    }

    #[test]
    fn reports_bad_nesting_with_the_element() {
        let err = scan("<robot>\n  <link name=\"a\">\n</robot>").unwrap_err();
        assert_eq!(
            err,
            "malformed XML at line 3, column 1: `</robot>` closes <link name=\"a\"> opened at line 2"
        );
        let err = scan("<robot>\n  <link name=\"a\">").unwrap_err();
        assert!(
            err.contains("<link name=\"a\"> opened at line 2 is never closed"),
            "{err}"
        );
    }

    #[test]
    fn reports_bad_tags_attributes_and_text() {
        let cases = [
            ("not xml", "text before the root element"),
            ("", "no root element"),
            (
                "<robot><link name=a/></robot>",
                "value of attribute `name` of <link> is not quoted",
            ),
            (
                "<robot><link name=\"a/></robot>",
                "value of attribute `name` of <link> is never closed",
            ),
            (
                "<robot><link name/></robot>",
                "attribute `name` of <link> has no",
            ),
            (
                "<robot><link name=\"a\" name=\"b\"/></robot>",
                "appears twice",
            ),
            ("<robot></robot><robot/>", "a second root element"),
            (
                "<robot><!-- open </robot>",
                "comment `<!--` is never closed",
            ),
            ("<robot></link></robot>", "`</link>` closes <robot>"),
            ("<robot><link", "the <link> tag is never closed"),
            ("<robot>< link/></robot>", "not followed by an element name"),
        ];
        for (text, expected) in cases {
            let err = scan(text).unwrap_err();
            assert!(err.contains(expected), "{text:?}: {err}");
        }
    }

    #[test]
    fn accepts_doctype_cdata_and_self_closing_root() {
        assert!(
            scan("<!DOCTYPE robot [<!ENTITY a \"b\">]><robot><x><![CDATA[<<>>]]></x></robot>")
                .is_ok()
        );
        let doc = scan("<robot name=\"r\"/>").unwrap();
        assert!(doc.children.is_empty());
    }
}
