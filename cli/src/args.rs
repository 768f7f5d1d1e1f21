//! A small argument parser shared by the spectra and design commands: positional arguments and
//! `--name value` / `--flag` options.

use std::collections::HashMap;

pub struct Args {
    pub positional: Vec<String>,
    values: HashMap<String, String>,
    flags: Vec<String>,
}

impl Args {
    /// `boolean`: the option names (without `--`) that take no value.
    pub fn parse(args: &[String], boolean: &[&str]) -> Result<Args, String> {
        let mut out = Args {
            positional: Vec::new(),
            values: HashMap::new(),
            flags: Vec::new(),
        };
        let mut it = args.iter();
        while let Some(a) = it.next() {
            if let Some(name) = a.strip_prefix("--") {
                if boolean.contains(&name) {
                    out.flags.push(name.to_string());
                } else {
                    let v = it
                        .next()
                        .ok_or_else(|| format!("option --{name} needs a value"))?;
                    out.values.insert(name.to_string(), v.clone());
                }
            } else {
                out.positional.push(a.clone());
            }
        }
        Ok(out)
    }

    pub fn flag(&self, name: &str) -> bool {
        self.flags.iter().any(|f| f == name)
    }

    pub fn str(&self, name: &str) -> Option<&str> {
        self.values.get(name).map(String::as_str)
    }

    pub fn f64_or(&self, name: &str, default: f64) -> Result<f64, String> {
        match self.values.get(name) {
            None => Ok(default),
            Some(v) => v
                .parse::<f64>()
                .map_err(|_| format!("--{name}: not a number: {v}")),
        }
    }

    pub fn f64_req(&self, name: &str) -> Result<f64, String> {
        let v = self
            .values
            .get(name)
            .ok_or_else(|| format!("missing --{name}"))?;
        v.parse::<f64>()
            .map_err(|_| format!("--{name}: not a number: {v}"))
    }

    pub fn usize_or(&self, name: &str, default: usize) -> Result<usize, String> {
        match self.values.get(name) {
            None => Ok(default),
            Some(v) => v
                .parse::<usize>()
                .map_err(|_| format!("--{name}: not a non-negative integer: {v}")),
        }
    }

    /// `--shard i/n` (0 ≤ i < n; default `0/1`): keep the items whose index `k` has `k % n == i`.
    pub fn shard(&self) -> Result<(usize, usize), String> {
        let Some(s) = self.values.get("shard") else {
            return Ok((0, 1));
        };
        let (i, n) = s
            .split_once('/')
            .ok_or_else(|| format!("--shard: expected i/n, got {s}"))?;
        let i: usize = i.parse().map_err(|_| format!("--shard: bad index {i}"))?;
        let n: usize = n.parse().map_err(|_| format!("--shard: bad count {n}"))?;
        if n == 0 || i >= n {
            return Err(format!("--shard: need 0 <= i < n, got {i}/{n}"));
        }
        Ok((i, n))
    }
}
