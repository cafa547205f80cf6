#pragma once
// Notes and warnings of a job (a folder resumed, a state in flight skipped, what a reader
// assumed), told to whoever runs it: the command line prints them on stderr (apps/progress.h),
// Python turns them into warnings.warn. As with progress (jobs/progress.h), the sink comes in
// through the job's options; an empty one says nothing. Jobs and analysis never write to the
// terminal themselves.
#include <functional>
#include <string>

namespace gs {

enum class MessageKind { Note, Warning };

// `text` is one line without "grainshock: " or a newline. Called from any thread of the job
// (an ensemble's workers): a sink must be thread-safe.
using MessageSink = std::function<void(MessageKind kind, const std::string& text)>;

inline void tell(const MessageSink& sink, MessageKind kind, const std::string& text) {
  if (sink) sink(kind, text);
}

}  // namespace gs
