//! The layout of the JSON documents: serde_json's compact output with `": "` after a key and
//! `", "` between an object's members, and line breaks where a document's [`Layout`] puts
//! them (one contour per line, one piece per line, …).
//!
//! The documents are derived `Serialize` types; [`to_text`] writes one with a
//! [`LayoutFormatter`], which only decides the whitespace: numbers, strings and their
//! escapes are serde_json's own. A rule names an object member or a list by its key and the
//! key of the object holding it (`("contours", "pieces")`: the `"pieces"` of an element of
//! a `"contours"` list), `""` for the document itself. Keys are strings (derived struct
//! members), as the rules need.

use serde::Serialize;
use serde_json::ser::{CharEscape, CompactFormatter, Formatter};
use std::io::{self, Write};

/// A member that starts a new line: `",\n"` and an indent instead of `", "` before its key.
#[derive(Debug)]
pub(crate) struct Break {
    /// The key of the object holding it (`""`: the document).
    pub(crate) parent: &'static str,
    /// Its key.
    pub(crate) key: &'static str,
    /// What follows the comma: a newline and the indent.
    pub(crate) line: &'static str,
}

/// A list whose elements each start a new line.
#[derive(Debug)]
pub(crate) struct List {
    /// The key of the object holding it (`""`: the document).
    pub(crate) parent: &'static str,
    /// Its key.
    pub(crate) key: &'static str,
    /// Written before an element (after its comma): a newline and the indent.
    pub(crate) line: &'static str,
    /// Whether the first element starts a new line too (else it follows the `[`).
    pub(crate) first: bool,
    /// Written before the closing `]` (`""`: the `]` follows the last element).
    pub(crate) close: &'static str,
}

/// Where a document breaks its lines; compact everywhere else.
#[derive(Debug)]
pub(crate) struct Layout {
    /// Members that start a line.
    pub(crate) breaks: &'static [Break],
    /// Lists with one element per line.
    pub(crate) lists: &'static [List],
}

impl Layout {
    /// The rules' own spelling of `key`, if a rule names it (as a key or a parent).
    fn known(&self, key: &[u8]) -> Option<&'static str> {
        let names = self.breaks.iter().flat_map(|b| [b.parent, b.key]);
        let mut names = names.chain(self.lists.iter().flat_map(|l| [l.parent, l.key]));
        names.find(|n| n.as_bytes() == key)
    }
}

/// An open object or list: its key (if a rule names it) and its list rule.
#[derive(Clone, Copy, Debug)]
struct Frame {
    name: Option<&'static str>,
    list: Option<&'static List>,
}

/// A serde_json formatter writing a [`Layout`].
#[derive(Debug)]
pub(crate) struct LayoutFormatter {
    layout: &'static Layout,
    /// The open objects and lists, innermost last.
    open: Vec<Frame>,
    /// The name of the value about to be written: its key, or its list's name.
    next: Option<&'static str>,
    /// While a key is written: whether it is the object's first, and its text so far (the
    /// comma and line break before it depend on it).
    key: Option<bool>,
    key_text: Vec<u8>,
}

impl LayoutFormatter {
    /// A formatter at the start of a document.
    pub(crate) fn new(layout: &'static Layout) -> LayoutFormatter {
        LayoutFormatter {
            layout,
            open: Vec::new(),
            next: Some(""),
            key: None,
            key_text: Vec::new(),
        }
    }

    fn parent(&self) -> Option<&'static str> {
        self.open.last().and_then(|f| f.name)
    }
}

impl Formatter for LayoutFormatter {
    fn begin_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        let (parent, name) = (self.parent(), self.next);
        let list = self
            .layout
            .lists
            .iter()
            .find(|l| Some(l.parent) == parent && Some(l.key) == name);
        self.open.push(Frame { name, list });
        w.write_all(b"[")
    }

    fn end_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        if let Some(l) = self.open.pop().and_then(|f| f.list) {
            w.write_all(l.close.as_bytes())?;
        }
        w.write_all(b"]")
    }

    fn begin_array_value<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        if !first {
            w.write_all(b",")?;
        }
        let frame = self.open.last().copied();
        self.next = frame.and_then(|f| f.name);
        match frame.and_then(|f| f.list) {
            Some(l) if !first || l.first => w.write_all(l.line.as_bytes()),
            _ => Ok(()),
        }
    }

    fn begin_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.open.push(Frame {
            name: self.next,
            list: None,
        });
        w.write_all(b"{")
    }

    fn end_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.open.pop();
        w.write_all(b"}")
    }

    fn begin_object_key<W: ?Sized + Write>(&mut self, _: &mut W, first: bool) -> io::Result<()> {
        // The separator waits for the key: whether it breaks the line depends on it.
        self.key = Some(first);
        self.key_text.clear();
        Ok(())
    }

    fn end_object_key<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        let first = self.key.take().unwrap_or(true);
        let parent = self.parent();
        if !first {
            let key = self.key_text.as_slice();
            let line = self
                .layout
                .breaks
                .iter()
                .find(|b| Some(b.parent) == parent && b.key.as_bytes() == key)
                .map_or(" ", |b| b.line);
            w.write_all(b",")?;
            w.write_all(line.as_bytes())?;
        }
        w.write_all(b"\"")?;
        w.write_all(&self.key_text)?;
        w.write_all(b"\"")?;
        self.next = self.layout.known(&self.key_text);
        Ok(())
    }

    fn begin_object_value<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        w.write_all(b": ")
    }

    fn begin_string<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        if self.key.is_some() {
            return Ok(());
        }
        w.write_all(b"\"")
    }

    fn end_string<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        if self.key.is_some() {
            return Ok(());
        }
        w.write_all(b"\"")
    }

    fn write_string_fragment<W: ?Sized + Write>(
        &mut self,
        w: &mut W,
        fragment: &str,
    ) -> io::Result<()> {
        if self.key.is_some() {
            self.key_text.extend_from_slice(fragment.as_bytes());
            return Ok(());
        }
        w.write_all(fragment.as_bytes())
    }

    fn write_char_escape<W: ?Sized + Write>(
        &mut self,
        w: &mut W,
        escape: CharEscape,
    ) -> io::Result<()> {
        if self.key.is_some() {
            return CompactFormatter.write_char_escape(&mut self.key_text, escape);
        }
        CompactFormatter.write_char_escape(w, escape)
    }
}

/// The text of `value` laid out by `layout`, with a final newline.
pub(crate) fn to_text<T: Serialize>(value: &T, layout: &'static Layout) -> String {
    let mut out = Vec::new();
    let mut ser = serde_json::Serializer::with_formatter(&mut out, LayoutFormatter::new(layout));
    // Writing to a Vec cannot fail, and the documents hold nothing serde_json refuses
    // (their keys are struct members, their raw numbers valid JSON).
    value
        .serialize(&mut ser)
        .expect("a JSON document serializes");
    out.push(b'\n');
    String::from_utf8(out).expect("serde_json writes UTF-8")
}

/// A big integer as an exact JSON number (its decimal digits, not a string).
#[derive(Debug)]
pub(crate) struct BigNumber<'a>(pub(crate) &'a num_bigint::BigInt);

impl Serialize for BigNumber<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        serde_json::value::RawValue::from_string(self.0.to_string())
            .map_err(serde::ser::Error::custom)?
            .serialize(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Serialize)]
    struct Doc {
        a: u8,
        b: Vec<Item>,
        c: Vec<[i32; 2]>,
        #[serde(rename = "d\"e")]
        d: &'static str,
    }

    #[derive(Serialize)]
    struct Item {
        x: i128,
        y: Vec<Item>,
    }

    const LAYOUT: Layout = Layout {
        breaks: &[Break {
            parent: "",
            key: "c",
            line: "\n ",
        }],
        lists: &[
            List {
                parent: "",
                key: "b",
                line: "\n  ",
                first: true,
                close: "\n ",
            },
            List {
                parent: "b",
                key: "y",
                line: "\n   ",
                first: false,
                close: "",
            },
        ],
    };

    /// Breaks where the rules say, compact elsewhere, keys and strings escaped by serde_json.
    #[test]
    fn lays_out_the_rules() {
        let leaf = |x| Item { x, y: Vec::new() };
        let doc = Doc {
            a: 1,
            b: vec![
                Item {
                    x: i128::MIN,
                    y: vec![leaf(2), leaf(3)],
                },
                leaf(4),
            ],
            c: vec![[1, -2], [3, 4]],
            d: "q\"\n",
        };
        let text = to_text(&doc, &LAYOUT);
        assert_eq!(
            text,
            "{\"a\": 1, \"b\": [\n  {\"x\": -170141183460469231731687303715884105728, \"y\": \
             [{\"x\": 2, \"y\": []},\n   {\"x\": 3, \"y\": []}]},\n  {\"x\": 4, \"y\": []}\n ],\n \
             \"c\": [[1,-2],[3,4]], \"d\\\"e\": \"q\\\"\\n\"}\n"
        );
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["d\"e"], "q\"\n");
    }

    #[test]
    fn big_numbers_are_exact_numbers() {
        let n: num_bigint::BigInt = "-123456789012345678901234567890123456789012345678901234567890"
            .parse()
            .unwrap();
        let text = to_text(&[BigNumber(&n)], &LAYOUT);
        assert_eq!(
            text,
            "[-123456789012345678901234567890123456789012345678901234567890]\n"
        );
    }
}
