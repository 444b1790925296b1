//! A `TAPE6` read line by line: the runs it has ended, the run being read, and where in
//! that run the reader is (its profile table, its spectral table).

use super::{
    ABSORPTION, AVERAGE, BENDING, CARD1_ECHO, IEMSCT_COLUMN, IRRADIANCE_SUM, Layout, LowtranTape6,
    MESSAGE_WORDS, Message, Opened, PROFILE_Z_P_T, RADIANCE_SUM, Tape6Run, Tape6Table, body,
    check_closed, check_rows, column_range, end_of_row, is_table_header, read_field, table_layout,
};
use crate::ParseError;
use crate::radtran::{Source, TextLine, read_int};

/// Where the reader is in a run's `ATMOSPHERIC PROFILES` table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Profile {
    /// Outside it.
    Outside,
    /// After its `ATMOSPHERIC PROFILES` banner, before its `I Z P T` header.
    Banner,
    /// In its Z P T table.
    Rows,
}

/// The state of a `TAPE6` being read, one line after another.
pub(super) struct Reader<'a> {
    src: Source<'a>,
    /// The runs ended so far, by their `CARD 5` echo.
    runs: Vec<Tape6Run>,
    /// The run being read.
    run: Tape6Run,
    /// IEMSCT, from the last echo of card 1.
    iemsct: Option<i64>,
    /// The spectral table whose rows follow, after its column header.
    in_table: Option<Layout>,
    /// Where the spectral table being read begins, until its `INTEGRATED` line.
    opened: Option<Opened>,
    /// Whether the run being read has a line yet.
    started: bool,
    profile: Profile,
}

impl<'a> Reader<'a> {
    /// A reader of the file `src`, before its first line.
    pub(super) fn new(src: Source<'a>) -> Self {
        Self {
            src,
            runs: Vec::new(),
            run: Tape6Run::default(),
            iemsct: None,
            in_table: None,
            opened: None,
            started: false,
            profile: Profile::Outside,
        }
    }

    /// Reads one line of the file.
    pub(super) fn line(&mut self, line: &TextLine<'_>) -> Result<(), ParseError> {
        let b = body(line);
        let t = b.trim();
        if !self.started {
            self.run.position = line.position();
            self.started = true;
        }
        if line.text.get(1..CARD1_ECHO.len()) == Some(&CARD1_ECHO[1..]) {
            self.iemsct = Some(card1_iemsct(self.src, line)?);
        }
        if self.profile_line(line, t)? {
            return Ok(());
        }
        if t.starts_with("CARD 5 *****") {
            return self.end_run(line);
        }
        if MESSAGE_WORDS.iter().any(|w| t.contains(w)) {
            self.run.messages.push(Message {
                text: t.to_owned(),
                position: line.position(),
            });
            if t.contains("IERROR NE 0") {
                self.run.rejected = true;
            }
        }
        if self.integral_line(line, t)? {
            return Ok(());
        }
        if is_table_header(t) {
            return self.table_header(line, t);
        }
        self.table_row(line)
    }

    /// Follows the run's `ATMOSPHERIC PROFILES` table, reading its rows; whether `line`
    /// (trimmed `t`) was its banner, its header or one of its rows.
    fn profile_line(&mut self, line: &TextLine<'_>, t: &str) -> Result<bool, ParseError> {
        if t.starts_with("ATMOSPHERIC PROFILES") && self.run.profile.is_empty() {
            self.profile = Profile::Banner;
            return Ok(true);
        }
        if self.profile == Profile::Banner && t.starts_with('I') && t.contains(" Z ") {
            self.profile = Profile::Rows;
            return Ok(true);
        }
        if self.profile == Profile::Rows {
            // A row starts with its level number I (I4, columns 1-4, whose first column is
            // also the printer's carriage control, a blank); anything else (the units line,
            // a blank line, a page break `1`, the next table) is not a row.
            let level = line.field(0, 4).trim();
            if line.text.starts_with(' ')
                && !level.is_empty()
                && level.bytes().all(|c| c.is_ascii_digit())
            {
                let zpt = profile_row(self.src, line, level)?;
                self.run.profile.push(zpt);
                return Ok(true);
            }
            if !self.run.profile.is_empty() {
                self.profile = Profile::Outside;
            }
        }
        Ok(false)
    }

    /// Ends the run at the echo of card 5 (`line`), and starts the next.
    fn end_run(&mut self, line: &TextLine<'_>) -> Result<(), ParseError> {
        check_closed(self.src, self.opened.take(), line.offset)?;
        self.run.iemsct = self.iemsct;
        self.runs.push(std::mem::take(&mut self.run));
        self.in_table = None;
        self.profile = Profile::Outside;
        self.started = false;
        Ok(())
    }

    /// Reads the run's integrated values and its bending; whether `line` (trimmed `t`) was
    /// one of their lines.
    fn integral_line(&mut self, line: &TextLine<'_>, t: &str) -> Result<bool, ParseError> {
        let src = self.src;
        if t.starts_with("INTEGRATED ABSORPTION") {
            self.close_table()?;
            self.run.integrated_absorption_per_cm = Some(read_field(
                src,
                line,
                ABSORPTION,
                "the integrated absorption in cm-1",
            )?);
            return Ok(true);
        }
        if t.starts_with("BENDING =") && self.run.bending_deg.is_none() {
            self.run.bending_deg = Some(read_field(src, line, BENDING, "the bending in degrees")?);
            return Ok(true);
        }
        if t.starts_with("AVERAGE TRANSMITTANCE") {
            self.run.average_transmittance =
                Some(read_field(src, line, AVERAGE, "the average transmittance")?);
            return Ok(true);
        }
        if t.starts_with("INTEGRATED RADIANCE") {
            self.close_table()?;
            self.run.integrated_radiance_w_cm2_sr = Some(read_field(
                src,
                line,
                RADIANCE_SUM,
                "the integrated radiance in W cm-2 sr-1",
            )?);
            return Ok(true);
        }
        if t.starts_with("INTEGRATED IRRADIANCE") {
            self.close_table()?;
            self.run.integrated_irradiance_w_cm2 = Some(read_field(
                src,
                line,
                IRRADIANCE_SUM,
                "the integrated irradiance in W cm-2",
            )?);
            return Ok(true);
        }
        Ok(false)
    }

    /// Ends the spectral table at an `INTEGRATED` line, which must follow its rows.
    fn close_table(&mut self) -> Result<(), ParseError> {
        check_rows(self.src, self.opened.take(), self.run.table.is_some())?;
        self.in_table = None;
        Ok(())
    }

    /// Starts (or, on a new page, goes on with) the spectral table whose column header is
    /// `line` (trimmed `t`): it must be LOWTRAN7's, of the run's IEMSCT and of the run's
    /// table.
    fn table_header(&mut self, line: &TextLine<'_>, t: &str) -> Result<(), ParseError> {
        let src = self.src;
        let Some(found) = table_layout(t) else {
            return Err(src.error(
                line.offset,
                line.text.len(),
                format!(
                    "expected one of the column headers LOWTRAN7 prints (FORMAT 900, 910, \
                     920, 921 or 930), found `{t}`"
                ),
            ));
        };
        if self.iemsct.is_some_and(|k| k != found.2) {
            return Err(src.error(
                line.offset,
                line.text.len(),
                format!(
                    "expected the table of an IEMSCT = {} run, as the echo of card 1 says, \
                     found the column header of IEMSCT = {}'s",
                    self.iemsct.unwrap_or(0),
                    found.2
                ),
            ));
        }
        if self.run.table.as_ref().is_some_and(|t| t.names != found.0) {
            return Err(src.error(
                line.offset,
                line.text.len(),
                "expected the rest of the run's table (a page's repeated header), found \
                 the header of another table",
            ));
        }
        self.in_table = Some(found);
        self.opened.get_or_insert(Opened {
            offset: line.offset,
            len: line.text.len(),
            line: line.position().line,
        });
        Ok(())
    }

    /// Reads `line` as a row of the spectral table being read, if it is one.
    fn table_row(&mut self, line: &TextLine<'_>) -> Result<(), ParseError> {
        let src = self.src;
        let Some((names, layout, _)) = self.in_table else {
            return Ok(());
        };
        // Page headers and unit lines (`1/CM  MICRONS …`) inside the table: not a row. A
        // row starts with its wavenumber, which LOWTRAN prints `F7.0` in columns 2-8
        // (`   710.`), or `F6.0` in columns 2-7 (FORMAT 928).
        let first = line.field(layout[0].start, layout[0].width).trim();
        let is_row = first.ends_with('.')
            && first.len() > 1
            && first[..first.len() - 1].bytes().all(|c| c.is_ascii_digit());
        if !is_row {
            return Ok(());
        }
        let what = format!(
            "a row of the IEMSCT = {} table",
            self.in_table.map_or(0, |l| l.2)
        );
        let table = self.run.table.get_or_insert_with(|| Tape6Table {
            names: names.to_vec(),
            columns: vec![Vec::new(); names.len()],
        });
        for (c, (&f, name)) in layout.iter().zip(names).enumerate() {
            let v = read_field(src, line, f, name)?;
            if c == 0
                && let Some(&last) = table.columns[0].last()
                && v <= last
            {
                return Err(src.error(
                    line.offset_of_column(f.start),
                    f.width,
                    format!("wavenumbers must strictly increase: {v} cm-1 follows {last} cm-1"),
                ));
            }
            if let Some((lo, hi, what)) = column_range(name)
                && !(lo..=hi).contains(&v)
            {
                return Err(src.error(
                    line.offset_of_column(f.start),
                    f.width,
                    format!("expected {what} from {lo} to {hi} for {name}, found {v}"),
                ));
            }
            table.columns[c].push(v);
        }
        let end = layout.last().map_or(0, |f| f.start + f.width);
        end_of_row(src, line, end, &what)
    }

    /// The runs read, once the file has ended at byte `end`.
    pub(super) fn finish(mut self, end: usize) -> Result<LowtranTape6, ParseError> {
        check_closed(self.src, self.opened, end)?;
        if self.started && (self.run.table.is_some() || !self.run.messages.is_empty()) {
            // A file cut before its last `CARD 5` echo: keep what it says.
            self.run.iemsct = self.iemsct;
            self.runs.push(self.run);
        }
        Ok(LowtranTape6 { runs: self.runs })
    }
}

/// IEMSCT, from the echo of card 1 (`line`).
fn card1_iemsct(src: Source<'_>, line: &TextLine<'_>) -> Result<i64, ParseError> {
    let text = line.field(IEMSCT_COLUMN, 5);
    let value = read_int(text).filter(|_| !text.trim().is_empty());
    let Some(value) = value else {
        return Err(src.error(
            line.offset_of_column(IEMSCT_COLUMN),
            5,
            format!(
                "expected IEMSCT (I5 in columns 26-30 of the echo of card 1), found `{}`",
                text.trim()
            ),
        ));
    };
    Ok(value)
}

/// The Z (km), P (mb) and T (K) of the profile's row `line`, of level number `level`.
fn profile_row(src: Source<'_>, line: &TextLine<'_>, level: &str) -> Result<[f64; 3], ParseError> {
    let mut zpt = [0.0; 3];
    for ((slot, f), what) in zpt
        .iter_mut()
        .zip(PROFILE_Z_P_T)
        .zip(["Z in km", "P in mb", "T in K"])
    {
        *slot = read_field(src, line, f, &format!("level {level}'s {what}"))?;
    }
    Ok(zpt)
}
