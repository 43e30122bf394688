//! The `validate` binary's command line (not part of the library): each
//! subcommand's options ([`args`]) and what it runs ([`commands`]).

pub mod args;
pub mod commands;
