// StoreWriter's part for time-keyed sequences (kiosk_sequences, kiosk_sequence_frames).
#include "runtime/core/TimeParse.h"
#include "runtime/io/StoreWriter.h"

namespace kiosk::io {

Diagnostics StoreWriter::createSequence(const SequenceSpec& spec) {
    Diagnostics d;
    if (!validTableName(spec.name)) {
        d.error("STORE_BAD_NAME", mDb.path(), spec.name,
                "sequence name must be letters, digits and '_'");
        return d;
    }
    auto st = mDb.prepare("INSERT OR IGNORE INTO kiosk_sequences VALUES (?,?,?,?,?,?)");
    if (!st) return st.diagnostics;
    st->bind(1, std::string_view(spec.name));
    st->bind(2, std::string_view(spec.units));
    st->bind(3, std::string_view(spec.variable));
    st->bindInt(4, spec.categorical ? 1 : 0);
    if (spec.nodata)
        st->bind(5, *spec.nodata);
    else
        st->bindNull(5);
    st->bind(6, std::string_view(spec.description));
    if (st->step() != SQLITE_DONE) d.add(mDb.error("STORE_SQL", kSequencesTable, spec.name));
    return d;
}

Diagnostics StoreWriter::addSequenceFrame(const std::string& sequence, int index,
                                          double epochSeconds, const std::string& table,
                                          double minValue, double maxValue) {
    Diagnostics d;
    auto st = mDb.prepare("INSERT INTO kiosk_sequence_frames VALUES (?,?,?,?,?,?,?)");
    if (!st) return st.diagnostics;
    st->bind(1, std::string_view(sequence));
    st->bindInt(2, index);
    st->bind(3, std::string_view(formatIso8601(epochSeconds)));
    st->bind(4, epochSeconds);
    st->bind(5, std::string_view(table));
    st->bind(6, minValue);
    st->bind(7, maxValue);
    if (st->step() != SQLITE_DONE)
        d.add(mDb.error("STORE_SQL", kFramesTable, sequence + " frame " + std::to_string(index)));
    return d;
}

std::vector<double> StoreWriter::sequenceTimes(const std::string& sequence) {
    std::vector<double> out;
    auto st = mDb.prepare(
        "SELECT time_epoch FROM kiosk_sequence_frames WHERE sequence_name = ? "
        "ORDER BY frame_index");
    if (!st) return out;
    st->bind(1, std::string_view(sequence));
    while (st->step() == SQLITE_ROW) out.push_back(st->columnDouble(0));
    return out;
}

std::optional<std::string> StoreWriter::sequenceUnits(const std::string& sequence) {
    auto st = mDb.prepare("SELECT units FROM kiosk_sequences WHERE name = ?");
    if (!st) return std::nullopt;
    st->bind(1, std::string_view(sequence));
    if (st->step() != SQLITE_ROW) return std::nullopt;
    return st->columnText(0);
}

}  // namespace kiosk::io
