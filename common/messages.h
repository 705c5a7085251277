#pragma once
// Where a library call's messages go. The library never prints: it hands each line to the
// caller's sink, and the apps decide where it lands (stdout, stderr, a terminal's status line).

#include <functional>
#include <string>

namespace hdimesh
{

enum class MessageKind
{
    Report,    ///< a report or table line, for the run's record (the apps' stdout)
    Trace,     ///< a diagnostic line of a stage's inner rounds (the apps' stderr)
    Progress,  ///< a status line that the next one replaces (a terminal's '\r' line)
};

/// Takes one message; its text ends with '\n' unless it is Progress. Empty: messages dropped.
using MessageSink = std::function<void(MessageKind kind, const std::string& text)>;

/// Formats like printf and hands the text to sink; nothing is formatted when sink is empty.
void emit(const MessageSink& sink, MessageKind kind, const char* format, ...)
    __attribute__((format(printf, 3, 4)));

}  // namespace hdimesh
