#include "ontology/detail/message_log.hpp"

#include <utility>

namespace geotex::detail {

void on_log_message(void* user_data, raptor_log_message* message) noexcept {
    try {
        LogEntry entry;
        entry.level = message->level;
        entry.text = message->text ? message->text : "";
        while (!entry.text.empty() && (entry.text.back() == '\n' || entry.text.back() == ' '))
            entry.text.pop_back();
        if (message->locator) {
            entry.line = message->locator->line > 0 ? message->locator->line : 0;
            entry.column = message->locator->column > 0 ? message->locator->column : 0;
        }
        static_cast<MessageLog*>(user_data)->entries.push_back(std::move(entry));
    } catch (...) {
        // Out of memory while keeping a message: the failing call still returns an error,
        // which the caller reports without this text.
    }
}

}  // namespace geotex::detail
