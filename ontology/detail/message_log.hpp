#pragma once
// Raptor's and Rasqal's messages: both report problems through a log handler; they are kept
// here (the library prints nothing) and turned into exceptions by the caller, with the line
// and column they give.

#include <raptor2.h>

#include <cstddef>
#include <string>
#include <vector>

namespace geotex::detail {

struct LogEntry {
    raptor_log_level level = RAPTOR_LOG_LEVEL_NONE;
    std::string text;
    long line = 0;    // 1-based, 0 = unknown
    long column = 0;  // 1-based, 0 = unknown
};

struct MessageLog {
    std::vector<LogEntry> entries;

    /// The first error logged at or after index `from`, or nullptr.
    const LogEntry* first_error(std::size_t from) const {
        for (std::size_t i = from; i < entries.size(); ++i)
            if (entries[i].level >= RAPTOR_LOG_LEVEL_ERROR) return &entries[i];
        return nullptr;
    }
};

/// A log handler for raptor_world_set_log_handler and rasqal_world_set_log_handler;
/// `user_data` is the MessageLog.
void on_log_message(void* user_data, raptor_log_message* message) noexcept;

}  // namespace geotex::detail
