#include <talus/base/input.h>
#include <talus/io/checkpointing.h>

#include <deal.II/base/utilities.h>

#include <boost/crc.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <vector>

namespace Talus
{
  namespace IO
  {
    namespace
    {
      namespace fs = std::filesystem;

      const std::string prefix     = "checkpoint-";
      const std::string tmp_prefix = "tmp-checkpoint-";

      [[noreturn]] void
      reject_checkpoint(const std::string &path, const std::string &what)
      {
        throw ExcInvalidInput("Cannot resume from the checkpoint <" + path +
                              ">: " + what);
      }

      /** Size and CRC-32 of a file. */
      std::pair<std::uintmax_t, unsigned int>
      size_and_crc(const fs::path &file)
      {
        std::ifstream      in(file, std::ios::binary);
        boost::crc_32_type crc;
        std::vector<char>  buffer(1 << 20);
        std::uintmax_t     size = 0;
        while (in)
          {
            in.read(buffer.data(), buffer.size());
            const auto n = in.gcount();
            crc.process_bytes(buffer.data(), n);
            size += n;
          }
        return {size, crc.checksum()};
      }

      /** Flush a file or directory to disk (best effort). */
      void
      sync_path(const fs::path &path)
      {
        const int fd = ::open(path.c_str(), O_RDONLY);
        if (fd >= 0)
          {
            ::fsync(fd);
            ::close(fd);
          }
      }

      /** The step of a directory name checkpoint-N, or -1. */
      long
      step_of(const std::string &name, const std::string &head)
      {
        if (name.compare(0, head.size(), head) != 0 ||
            name.size() == head.size())
          return -1;
        const std::string digits = name.substr(head.size());
        if (!std::all_of(digits.begin(), digits.end(), [](const char c) {
              return c >= '0' && c <= '9';
            }))
          return -1;
        return std::stol(digits);
      }

      /** The checkpoint-N subdirectories of @p root, sorted by N. */
      std::vector<std::pair<long, fs::path>>
      list_checkpoints(const fs::path &root, const std::string &head)
      {
        std::vector<std::pair<long, fs::path>> found;
        std::error_code                        error;
        if (!fs::is_directory(root, error))
          return found;
        for (const auto &entry : fs::directory_iterator(root, error))
          if (entry.is_directory())
            {
              const long n = step_of(entry.path().filename().string(), head);
              if (n >= 0)
                found.emplace_back(n, entry.path());
            }
        std::sort(found.begin(), found.end());
        return found;
      }
    } // namespace


    const std::string Checkpointing::format_name = "talus-checkpoint";


    void
    Checkpointing::declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      prm.enter_subsection("Checkpoint");
      {
        prm.declare_entry(
          "every steps",
          "0",
          Patterns::Integer(0),
          "Write a checkpoint after every this many accepted time steps "
          "[-]; 0: not by steps. A run that fails (a step that cannot be "
          "solved, lost points with 'abort on lost material points') "
          "writes one before it stops whenever checkpoints are on.");
        prm.declare_entry(
          "every minutes",
          "0",
          Patterns::Double(0),
          "Write a checkpoint after the first step that ends this much wall "
          "time after the start or the last checkpoint [min]; 0: not by "
          "wall time. Both criteria may be set.");
        prm.declare_entry(
          "stop after minutes",
          "0",
          Patterns::Double(0),
          "Stop the run after the first step that ends this much wall time "
          "after its start [min], with a checkpoint of that step (also if "
          "'every steps' and 'every minutes' are 0) named in the message, "
          "so that a batch job ends before its limit and the next one "
          "resumes; exit code 1. 0: no limit.");
        prm.declare_entry("keep",
                          "2",
                          Patterns::Integer(1),
                          "Number of the newest checkpoints kept; older ones "
                          "are deleted after a new one is complete [-].");
        prm.declare_entry(
          "directory",
          "",
          Patterns::DirectoryName(),
          "Directory of the checkpoints (one subdirectory checkpoint-N per "
          "checkpoint, N the step); empty: <output directory>/checkpoints.");
        prm.declare_entry(
          "resume",
          "false",
          Patterns::Bool(),
          "Continue from the newest complete checkpoint in 'directory' "
          "instead of starting at t = 0 (the command line 'talus --resume "
          "<checkpoint or directory> <file>' does the same). The time "
          "series and the visualization index continue from the "
          "checkpoint: rows and outputs after it are dropped.");
      }
      prm.leave_subsection();
    }


    void
    Checkpointing::parse_parameters(dealii::ParameterHandler &prm,
                                    const std::string        &output_directory)
    {
      prm.enter_subsection("Checkpoint");
      every_steps          = prm.get_integer("every steps");
      every_minutes        = prm.get_double("every minutes");
      stop_after_minutes   = prm.get_double("stop after minutes");
      keep                 = prm.get_integer("keep");
      checkpoint_directory = prm.get("directory");
      resume               = prm.get_bool("resume");
      prm.leave_subsection();
      if (checkpoint_directory.empty())
        checkpoint_directory = output_directory + "/checkpoints";
      last_write = std::chrono::steady_clock::now();
      start      = last_write;
    }


    bool
    Checkpointing::stop_due(const MPI_Comm communicator) const
    {
      if (stop_after_minutes <= 0.)
        return false;
      const double minutes =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count() /
        60.;
      return dealii::Utilities::MPI::broadcast(communicator,
                                               minutes >= stop_after_minutes,
                                               0);
    }


    std::string
    Checkpointing::wall_limit_message(const unsigned int step,
                                      const double       time,
                                      const std::string &path) const
    {
      std::ostringstream msg;
      msg << "The run stopped at its wall-time limit ('stop after "
             "minutes' = "
          << stop_after_minutes << " in subsection <Checkpoint>) after step "
          << step << ", t = " << time << " s.";
      msg << " The state after this step is in the checkpoint <" << path
          << ">: resume from it.";
      return msg.str();
    }


    std::string
    Checkpointing::lost_points_note(const unsigned int step,
                                    const std::string &path)
    {
      return " The state after this step (" + std::to_string(step) +
             ", without the lost points) is in the checkpoint <" + path +
             ">: resume from it with 'abort on lost material points = "
             "false' to continue without them.";
    }


    bool
    Checkpointing::due(const unsigned int step,
                       const MPI_Comm     communicator) const
    {
      if (every_steps > 0 && step % every_steps == 0)
        return true;
      if (every_minutes <= 0.)
        return false;
      const double minutes = std::chrono::duration<double>(
                               std::chrono::steady_clock::now() - last_write)
                               .count() /
                             60.;
      return dealii::Utilities::MPI::broadcast(communicator,
                                               minutes >= every_minutes,
                                               0);
    }


    std::string
    Checkpointing::write(
      const unsigned int                                       step,
      const double                                             time,
      const std::string                                       &reason,
      const std::function<void(const std::string &directory)> &writer,
      const MPI_Comm                                           communicator)
    {
      std::ostringstream time_text;
      time_text << std::setprecision(17) << time;
      const std::map<std::string, std::string> info = {
        {"step", std::to_string(step)},
        {"time", time_text.str()},
        {"ranks",
         std::to_string(dealii::Utilities::MPI::n_mpi_processes(communicator))},
        {"reason", reason},
        {"problem", problem},
        {"parameter_file", InputFile::name()}};
      const bool root =
        dealii::Utilities::MPI::this_mpi_process(communicator) == 0;
      const std::string number = dealii::Utilities::int_to_string(step, 8);
      const fs::path    root_dir(checkpoint_directory);
      const fs::path    tmp   = root_dir / (tmp_prefix + number);
      const fs::path    final = root_dir / (prefix + number);

      int         ok = 1;
      std::string problem;
      if (root)
        {
          std::error_code error;
          fs::create_directories(root_dir, error);
          fs::remove_all(tmp, error);
          fs::create_directory(tmp, error);
          if (error)
            {
              ok      = 0;
              problem = error.message();
            }
        }
      if (dealii::Utilities::MPI::min(ok, communicator) == 0)
        InputFile::reject("Checkpoint",
                          "directory",
                          checkpoint_directory,
                          "a directory in which a checkpoint can be written "
                          "(creating <" +
                            tmp.string() + "> failed: " + problem + ")");

      writer(tmp.string());
      MPI_Barrier(communicator);

      if (root)
        {
          // every file the writer made, with size and checksum
          std::vector<std::string> files;
          for (const auto &entry : fs::directory_iterator(tmp))
            if (entry.is_regular_file())
              files.push_back(entry.path().filename().string());
          std::sort(files.begin(), files.end());
          std::ostringstream manifest;
          manifest << format_name << ' ' << format_version << '\n';
          for (const auto &[key, value] : info)
            manifest << "key " << key << " = " << value << '\n';
          for (const auto &name : files)
            {
              sync_path(tmp / name);
              const auto [size, crc] = size_and_crc(tmp / name);
              manifest << "file " << size << ' ' << std::hex << std::setw(8)
                       << std::setfill('0') << crc << std::dec
                       << std::setfill(' ') << ' ' << name << '\n';
            }
          manifest << "end\n";
          {
            std::ofstream out(tmp / "manifest");
            out << manifest.str();
            out.flush();
            ok = out ? 1 : 0;
          }
          sync_path(tmp / "manifest");
          sync_path(tmp);
          if (ok)
            {
              // replace a checkpoint of the same step (a failure checkpoint
              // after a regular one): move it aside first, so that one
              // complete copy exists at every moment
              std::error_code error;
              const fs::path  old = root_dir / ("old-" + prefix + number);
              if (fs::exists(final))
                fs::rename(final, old, error);
              fs::rename(tmp, final, error);
              if (error)
                {
                  ok      = 0;
                  problem = error.message();
                }
              fs::remove_all(old, error);
              sync_path(root_dir);
              // keep the newest ones
              const auto existing = list_checkpoints(root_dir, prefix);
              for (std::size_t i = 0; i + keep < existing.size(); ++i)
                fs::remove_all(existing[i].second, error);
            }
          else
            problem = "the manifest could not be written";
        }
      if (dealii::Utilities::MPI::min(ok, communicator) == 0)
        InputFile::reject("Checkpoint",
                          "directory",
                          checkpoint_directory,
                          "a directory in which a checkpoint can be written "
                          "(" +
                            problem + ")");
      last_write = std::chrono::steady_clock::now();
      return final.string();
    }


    std::string
    Checkpointing::find_newest(const std::string &path)
    {
      std::error_code error;
      if (fs::exists(fs::path(path) / "manifest", error))
        return path;
      if (!fs::is_directory(path, error))
        throw ExcInvalidInput("Cannot resume: <" + path +
                              "> is neither a checkpoint (a directory with a "
                              "file 'manifest') nor a directory of "
                              "checkpoints.");
      const auto found = list_checkpoints(path, prefix);
      for (auto it = found.rbegin(); it != found.rend(); ++it)
        if (fs::exists(it->second / "manifest", error))
          return it->second.string();
      throw ExcInvalidInput("Cannot resume: the directory <" + path +
                            "> holds no complete checkpoint (no "
                            "subdirectory checkpoint-N with a manifest).");
    }


    std::string
    Checkpointing::find_and_check(const std::string &path,
                                  const MPI_Comm     communicator,
                                  const std::string &problem)
    {
      std::string found, error;
      if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
        try
          {
            found           = find_newest(path);
            const auto info = read_manifest(found);
            const auto it   = info.find("problem");
            // checkpoints without the key are those of the MPM problem
            const std::string written =
              it == info.end() ? std::string("mpm") : it->second;
            if (written != problem)
              reject_checkpoint(found,
                                "it was written by a run of 'problem = " +
                                  written + "', the parameter file <" +
                                  InputFile::name() +
                                  "> sets 'problem = " + problem + "'.");
          }
        catch (const ExcInvalidInput &e)
          {
            error = e.what();
          }
      error = dealii::Utilities::MPI::broadcast(communicator, error, 0);
      if (!error.empty())
        throw ExcInvalidInput(error);
      return dealii::Utilities::MPI::broadcast(communicator, found, 0);
    }


    std::map<std::string, std::string>
    Checkpointing::read_manifest(const std::string &path)
    {
      const fs::path dir(path);
      std::ifstream  in(dir / "manifest");
      if (!in)
        reject_checkpoint(path,
                          "the file <" + (dir / "manifest").string() +
                            "> cannot be read; this is not a Talus "
                            "checkpoint.");
      std::string line;
      std::getline(in, line);
      {
        std::istringstream first(line);
        std::string        name;
        unsigned int       version = 0;
        first >> name >> version;
        if (name != format_name)
          reject_checkpoint(path,
                            "the file <" + (dir / "manifest").string() +
                              "> does not start with '" + format_name +
                              "': this is not a Talus checkpoint.");
        if (version != format_version)
          reject_checkpoint(path,
                            "checkpoint format version " +
                              std::to_string(version) +
                              ", this Talus reads version " +
                              std::to_string(format_version) + ".");
      }
      std::map<std::string, std::string> info;
      bool                               complete = false;
      while (std::getline(in, line))
        {
          if (line == "end")
            {
              complete = true;
              break;
            }
          std::istringstream words(line);
          std::string        kind;
          words >> kind;
          if (kind == "key")
            {
              std::string key, equals, value;
              words >> key >> equals;
              std::getline(words >> std::ws, value);
              info[key] = value;
            }
          else if (kind == "file")
            {
              std::uintmax_t size = 0;
              std::string    crc_text, name;
              words >> size >> crc_text;
              std::getline(words >> std::ws, name);
              const fs::path  file = dir / name;
              std::error_code error;
              if (!fs::is_regular_file(file, error))
                reject_checkpoint(path,
                                  "the file <" + file.string() +
                                    "> listed in its manifest is missing.");
              const auto [actual_size, crc] = size_and_crc(file);
              if (actual_size != size)
                reject_checkpoint(path,
                                  "the file <" + file.string() + "> has " +
                                    std::to_string(actual_size) +
                                    " bytes, its manifest says " +
                                    std::to_string(size) +
                                    " (truncated or overwritten).");
              std::ostringstream hex;
              hex << std::hex << std::setw(8) << std::setfill('0') << crc;
              if (hex.str() != crc_text)
                reject_checkpoint(path,
                                  "the file <" + file.string() +
                                    "> has the CRC-32 " + hex.str() +
                                    ", its manifest says " + crc_text +
                                    " (damaged).");
            }
          else
            reject_checkpoint(path,
                              "the line '" + line + "' of <" +
                                (dir / "manifest").string() +
                                "> is not understood.");
        }
      if (!complete)
        reject_checkpoint(path,
                          "the manifest <" + (dir / "manifest").string() +
                            "> is truncated (no final 'end' line).");
      return info;
    }
  } // namespace IO
} // namespace Talus
