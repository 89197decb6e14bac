// What the command-line tools write (docs/interfaces.md): the trajectory CSV, the JSON summaries of a run and of a
// recorded stream, and a text file or standard output.
#pragma once

#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include "run.hpp"

namespace top_sim {

// The trajectory CSV (docs/interfaces.md): each number is std::to_chars' shortest text that reads back as the same
// double (NaN as "nan"), formatted straight into a block buffer written a block at a time; flush() before checking
// the stream.
class CsvWriter {
 public:
  explicit CsvWriter(std::ostream& os);
  ~CsvWriter() { flush(); }
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  void header();
  void row(const Snapshot& s);
  void flush();

 private:
  static constexpr std::size_t kBlock = 1 << 16;    // bytes per write
  static constexpr std::size_t kField = 32;         // room for one field and its comma (a number: kNumberChars)
  std::ostream& os_;
  std::unique_ptr<char[]> buf_;                     // kBlock and room for one more row
  std::size_t used_ = 0;
};

// The JSON summary of docs/interfaces.md.
std::string summary_json(const Scene& scene, const RunResult& r);

// Writes `text` to `path` ("-" = standard output, "" = nothing); false after "TOOL: FLAG = 'PATH': ..." on stderr.
bool write_text_file(const std::string& tool, const std::string& flag, const std::string& path,
                     const std::string& text);

// Where a recorded stream came from and what only the recording's reader knows.
struct RecordedSource {
  std::string bag, topic, top;
  const Scene* scene = nullptr;  // --scene: its method, model, normal force; phi_star from its stationary solver
  std::optional<double> phi_star;
  std::string phi_star_source, stationary_note;
  std::uint64_t skipped = 0;  // messages whose sim_time did not advance
};

// The JSON summary of a recorded stream (top_sim_bag): top_sim_run's keys where a recording can give them; the
// others are null and "unavailable" says why.
std::string summary_json(const RecordedSource& source, const SampledSummary& s);

}  // namespace top_sim
