#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/io/StoreWriter.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace kiosk::import {

/**
 * @brief The temporary-file-and-rename transaction of every import: `fn(StoreWriter&)` works on
 * `STORE.tmp-XXXXXX` (a copy of the store when it exists), which replaces the store only when
 * `fn` and the commit succeed. On any error the temporary file is removed, the store is
 * untouched, and diagnostics about the temporary name are reported against the store's name.
 */
template <class Fn>
Diagnostics withTempStore(const std::filesystem::path& store, Fn&& fn) {
    namespace fs = std::filesystem;
    Diagnostics d;
    const std::string storePath = store.string();
    if (storePath.empty()) {
        d.error("IMPORT_USAGE", "", "--store", "no store given");
        return d;
    }
    std::string tmpl = storePath + ".tmp-XXXXXX";
    std::vector<char> buf(tmpl.begin(), tmpl.end());
    buf.push_back('\0');
    const int fd = mkstemp(buf.data());
    if (fd < 0) {
        d.error("IMPORT_WRITE", storePath, "",
                std::string("cannot create a temporary file beside the store: ") +
                    std::strerror(errno));
        return d;
    }
    // mkstemp makes the file private; the store gets the usual umask-derived mode.
    const mode_t mask = umask(0);
    umask(mask);
    fchmod(fd, 0666 & ~mask);
    close(fd);
    const std::string tmp(buf.data());
    std::error_code ec;
    const bool exists = fs::exists(store, ec);
    if (exists) {
        fs::copy_file(store, tmp, fs::copy_options::overwrite_existing, ec);
        if (ec) {
            fs::remove(tmp, ec);
            d.error("IMPORT_WRITE", storePath, "", "cannot copy the store: " + ec.message());
            return d;
        }
    }
    {
        auto w = io::StoreWriter::open(tmp, !exists);
        if (!w) {
            d.append(w.diagnostics);
        } else {
            // Nothing may escape as an exception (allocation failure, filesystem errors): the
            // temporary file must still be removed below.
            try {
                d.append(fn(**w));
            } catch (const std::exception& e) {
                d.error("IMPORT_INTERNAL", storePath, "",
                        std::string("import aborted: ") + e.what());
            }
            if (!d.hasErrors()) d.append((*w)->commit());
        }
    }
    if (d.hasErrors()) {
        fs::remove(tmp, ec);
        // The temp name means nothing to the user: errors about it are errors about the store.
        Diagnostics out;
        for (auto item : d.items()) {
            if (item.file == tmp) item.file = storePath;
            out.add(item);
        }
        return out;
    }
    fs::rename(tmp, store, ec);
    if (ec) {
        fs::remove(tmp, ec);
        d.error("IMPORT_WRITE", storePath, "", "cannot replace the store: " + ec.message());
    }
    return d;
}

}  // namespace kiosk::import
