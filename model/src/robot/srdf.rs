//! The parts of a MoveIt SRDF (Semantic Robot Description Format) a pushing planner
//! needs: the link pairs never checked for self-collision (`<disable_collisions>`) and the
//! planning groups given as a chain (`<group><chain base_link tip_link/></group>`), which
//! name the arm. Everything else (group states, end effectors, virtual joints) is left
//! alone, as MoveIt's own parser leaves what it does not use.

use crate::error::{Error, Result};
use std::path::Path;

/// A planning group: its name and, where it is given as one, its chain.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// The group's name (`panda_arm`).
    pub name: String,
    /// The chain's base and tip links, if the group is a chain.
    pub chain: Option<(String, String)>,
}

/// A pair of links never checked against each other.
#[derive(Clone, Debug, PartialEq)]
pub struct DisabledPair {
    /// One link.
    pub link1: String,
    /// The other.
    pub link2: String,
    /// Why, as the SRDF says (`Adjacent`, `Never`, ...), if it does.
    pub reason: Option<String>,
}

/// What pushplan reads of an SRDF.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Srdf {
    /// The planning groups, in the file's order.
    pub groups: Vec<Group>,
    /// The pairs never checked, in the file's order.
    pub disabled: Vec<DisabledPair>,
}

impl Srdf {
    /// Reads the SRDF at `path` (a regular file of at most the URDF size limit).
    pub fn read(path: &Path) -> Result<Srdf> {
        let text = crate::input::read_text(path, crate::input::MAX_URDF_BYTES)
            .map_err(|message| Error::io(path, message))?;
        Srdf::parse(&text, path)
    }

    /// Parses SRDF text; `path` names it in errors.
    pub fn parse(text: &str, path: &Path) -> Result<Srdf> {
        let parse_error = |field: String, message: String| Error::Parse {
            file: path.to_path_buf(),
            field,
            message,
        };
        let document = roxmltree::Document::parse(text)
            .map_err(|e| parse_error(String::new(), format!("not XML: {e}")))?;
        let root = document.root_element();
        if root.tag_name().name() != "robot" {
            return Err(parse_error(
                String::new(),
                format!(
                    "the root element is <{}>, not <robot>",
                    root.tag_name().name()
                ),
            ));
        }
        let mut srdf = Srdf::default();
        let attribute = |node: roxmltree::Node, field: &str, name: &str| {
            node.attribute(name)
                .filter(|v| !v.is_empty())
                .map(str::to_string)
                .ok_or_else(|| parse_error(field.to_string(), format!("needs a {name} attribute")))
        };
        for node in root.children().filter(|n| n.is_element()) {
            match node.tag_name().name() {
                "disable_collisions" => {
                    let field = format!("disable_collisions[{}]", srdf.disabled.len());
                    srdf.disabled.push(DisabledPair {
                        link1: attribute(node, &field, "link1")?,
                        link2: attribute(node, &field, "link2")?,
                        reason: node.attribute("reason").map(str::to_string),
                    });
                }
                "group" => {
                    let field = format!("group[{}]", srdf.groups.len());
                    let chain = match node
                        .children()
                        .find(|c| c.is_element() && c.tag_name().name() == "chain")
                    {
                        Some(c) => Some((
                            attribute(c, &format!("{field}.chain"), "base_link")?,
                            attribute(c, &format!("{field}.chain"), "tip_link")?,
                        )),
                        None => None,
                    };
                    srdf.groups.push(Group {
                        name: attribute(node, &field, "name")?,
                        chain,
                    });
                }
                _ => {}
            }
        }
        Ok(srdf)
    }

    /// The chain of the group named `name`, or, without a name, of the only group given
    /// as a chain. Errors say which groups there are.
    pub fn chain(&self, name: Option<&str>) -> std::result::Result<(String, String), String> {
        let chains: Vec<&Group> = self.groups.iter().filter(|g| g.chain.is_some()).collect();
        let names = || crate::input::name_list(chains.iter().map(|g| g.name.as_str()));
        match name {
            Some(name) => match self.groups.iter().find(|g| g.name == name) {
                Some(Group {
                    chain: Some(chain), ..
                }) => Ok(chain.clone()),
                Some(_) => Err(format!(
                    "group '{name}' is not given as a <chain>; the chain groups are {}",
                    names()
                )),
                None => Err(format!(
                    "no group named '{name}'; the chain groups are {}",
                    names()
                )),
            },
            None => match chains.as_slice() {
                [one] => Ok(one.chain.clone().expect("a chain group")),
                [] => Err("no group is given as a <chain>".into()),
                _ => Err(format!(
                    "{} groups are chains ({}): name one with robot.group",
                    chains.len(),
                    names()
                )),
            },
        }
    }
}
