//! The iterator every reader of records shares: records until the end or the first error.

/// A reader of records, one at a time, that stops after its first error: the CL, points, path
/// CSV, joint CSV and inter-file readers. A reader gives [`read_record`](Self::read_record) and
/// its flag ([`stopped`](Self::stopped)); its `Iterator::next` is
/// [`next_record`](Self::next_record), written once here.
pub trait RecordReader {
    /// What one read yields.
    type Record;
    /// Why a read failed.
    type Error;

    /// The next record; `Ok(None)` at the end of the input.
    fn read_record(&mut self) -> Result<Option<Self::Record>, Self::Error>;

    /// The reader's flag: set once it reached the end or failed.
    fn stopped(&mut self) -> &mut bool;

    /// The next record, until the end of the input or the first error (which is returned); then
    /// `None` for ever: nothing is read after an error.
    #[inline]
    fn next_record(&mut self) -> Option<Result<Self::Record, Self::Error>> {
        if *self.stopped() {
            return None;
        }
        let item = self.read_record().transpose();
        *self.stopped() = !matches!(item, Some(Ok(_)));
        item
    }
}

/// Makes a reader type (generic over `R: BufRead`) a [`RecordReader`] and an `Iterator` of
/// `Result<RECORD, ERROR>`: `record_reader!(Reader, RECORD, ERROR, read, flag)`, where the
/// reader's method `read(&mut self) -> Result<Option<RECORD>, ERROR>` reads one record and its
/// `bool` field `flag` is the [`stopped`](RecordReader::stopped) flag (false when created).
#[macro_export]
macro_rules! record_reader {
    ($reader:ident, $record:ty, $error:ty, $read:ident, $flag:ident) => {
        impl<R: ::std::io::BufRead> $crate::RecordReader for $reader<R> {
            type Record = $record;
            type Error = $error;

            fn read_record(&mut self) -> ::core::result::Result<Option<$record>, $error> {
                self.$read()
            }

            fn stopped(&mut self) -> &mut bool {
                &mut self.$flag
            }
        }

        impl<R: ::std::io::BufRead> ::core::iter::Iterator for $reader<R> {
            type Item = ::core::result::Result<$record, $error>;

            fn next(&mut self) -> Option<Self::Item> {
                $crate::RecordReader::next_record(self)
            }
        }
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reads the numbers of a list; an odd one is an error.
    struct Evens<'a> {
        rest: &'a [u32],
        stopped: bool,
    }

    impl RecordReader for Evens<'_> {
        type Record = u32;
        type Error = u32;
        fn read_record(&mut self) -> Result<Option<u32>, u32> {
            let Some((&first, rest)) = self.rest.split_first() else { return Ok(None) };
            self.rest = rest;
            if first % 2 == 0 { Ok(Some(first)) } else { Err(first) }
        }
        fn stopped(&mut self) -> &mut bool {
            &mut self.stopped
        }
    }

    #[test]
    fn nothing_is_read_after_the_first_error() {
        let mut reader = Evens { rest: &[2, 4, 5, 6], stopped: false };
        let items: Vec<_> = std::iter::from_fn(|| reader.next_record()).collect();
        assert_eq!(items, [Ok(2), Ok(4), Err(5)]);
        assert_eq!(reader.rest, [6], "the record after the error is not read");
        let mut empty = Evens { rest: &[], stopped: false };
        assert_eq!(empty.next_record(), None);
        assert_eq!(empty.next_record(), None);
    }
}
