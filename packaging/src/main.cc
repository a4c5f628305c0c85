// hubrt-board-info — what packaging and the deploy guide need to know about a board, read with the
// board loader hubd uses (so a broken board file fails here with the same located message):
//
//   hubrt-board-info arch boards/rpi4-tool-ecu.yaml                 arm64
//   hubrt-board-info package boards/rpi4-tool-ecu.yaml --hubs-dir hubs   JSON for the package
//   hubrt-board-info deploy-docs --doc docs/deploy.md boards/*.yaml [--check]
//
// Exit codes: 0 done, 1 --check found the guide out of date, 2 bad arguments or files.
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/packaging/board_facts.h"
#include "hubrt/packaging/wiring_tables.h"

namespace hubrt::packaging {
namespace {

constexpr int kExitOutdated = 1;
constexpr int kExitError = 2;

int fail(const std::string& message) {
  std::cerr << "hubrt-board-info: " << message << "\n";
  return kExitError;
}

int print_arch(const std::string& board_file) {
  auto board = hal::load_board(board_file);
  if (!board) return fail(board.error().message);
  std::cout << board->arch << "\n";
  return 0;
}

int print_package_facts(const std::string& board_file, const std::string& hubs_dir) {
  auto board = hal::load_board(board_file);
  if (!board) return fail(board.error().message);
  if (board->hubs.size() != 1) {
    return fail(fmt::format("{}: board '{}' is wired for {} hubs; a package runs exactly one", board_file,
                            board->name, board->hubs.size()));
  }
  const std::string& hub_type = board->hubs.front();
  auto hub = config::load_hub_config(fmt::format("{}/{}/{}.yaml", hubs_dir, hub_type, hub_type));
  if (!hub) return fail(hub.error().message);
  auto facts = package_facts(*board, *hub);
  if (!facts) return fail(facts.error().message);
  std::cout << to_json(*facts) << "\n";
  return 0;
}

int update_deploy_docs(const std::string& doc_file, const std::vector<std::string>& board_files, bool check) {
  std::vector<hal::BoardConfig> boards;
  for (const std::string& file : board_files) {
    auto board = hal::load_board(file);
    if (!board) return fail(board.error().message);
    boards.push_back(std::move(*board));
  }
  std::ifstream in(doc_file, std::ios::binary);
  if (!in) return fail(fmt::format("cannot read {}", doc_file));
  const std::string document((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto updated = replace_generated_section(document, wiring_section(std::move(boards)));
  if (!updated) return fail(fmt::format("{}: {}", doc_file, updated.error().message));
  if (*updated == document) return 0;
  if (check) {
    std::cerr << "hubrt-board-info: the wiring tables in " << doc_file
              << " differ from the board files: run `make deploy-docs`\n";
    return kExitOutdated;
  }
  std::ofstream out(doc_file, std::ios::binary | std::ios::trunc);
  if (!(out << *updated)) return fail(fmt::format("cannot write {}", doc_file));
  std::cerr << "hubrt-board-info: updated the wiring tables in " << doc_file << "\n";
  return 0;
}

}  // namespace
}  // namespace hubrt::packaging

int main(int argc, char** argv) {
  CLI::App app{"hubrt-board-info — board facts for packaging and the deploy guide"};
  app.require_subcommand(1);
  int exit_code = 0;

  std::string board_file;
  auto* arch = app.add_subcommand("arch", "Print the board's Debian architecture");
  arch->add_option("board", board_file, "Board file")->required();
  arch->callback([&] { exit_code = hubrt::packaging::print_arch(board_file); });

  std::string hubs_dir = "hubs";
  auto* package = app.add_subcommand("package", "Print what the board's package is made from, as JSON");
  package->add_option("board", board_file, "Board file")->required();
  package->add_option("--hubs-dir", hubs_dir, "Folder of hub types (<dir>/<hub>/<hub>.yaml)");
  package->callback([&] { exit_code = hubrt::packaging::print_package_facts(board_file, hubs_dir); });

  std::string doc_file;
  std::vector<std::string> board_files;
  bool check = false;
  auto* docs = app.add_subcommand("deploy-docs", "Regenerate the wiring tables of the deploy guide");
  docs->add_option("--doc", doc_file, "The deploy guide (Markdown with the generated-section markers)")
      ->required();
  docs->add_option("boards", board_files, "Board files")->required();
  docs->add_flag("--check", check, "Do not write: exit 1 if the tables are out of date");
  docs->callback([&] { exit_code = hubrt::packaging::update_deploy_docs(doc_file, board_files, check); });

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  return exit_code;
}
