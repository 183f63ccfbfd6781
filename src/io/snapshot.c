/* Snapshots in HDF5 with an XDMF companion: see snapshot.h.
 *
 * Layout (SWIFT's, so that swiftsimio, woma and planetary analysis scripts
 * read it unchanged):
 *   /Header          Time, BoxSize[3], NumPart_*[6], Dimension, MassTable, ...
 *   /Units, /InternalCodeUnits   the five base units in cgs
 *   /Parameters      the used parameters (whole YAML text + one attribute per key)
 *   /Code /Cosmology /Policy /HydroScheme /GravityScheme /SubgridScheme /RuntimePars
 *   /PartType0/NAME  one dataset per field of BOLIDE_PART_FIELDS, N or N x ncomp,
 *                    with the unit attributes swiftsimio reads
 *                    ("U_M exponent", ..., "Conversion factor to CGS ...").
 *
 * Every HDF5 call is checked; a failure closes the file, removes the temporary
 * file and stops with one line. */
#include "src/io/snapshot.h"

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <libgen.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "config.h"
#include "src/error.h"
#include "src/version.h"

#if defined(HAVE_MPI) && defined(H5_HAVE_PARALLEL)
#include <mpi.h>
#define SNAPSHOT_PARALLEL 1
#endif

/** State of one file being written. */
struct snapshot_writer {
  const char *path; /**< final name */
  char tmp[4096];   /**< temporary name being written */
  hid_t file;       /**< HDF5 file (or H5I_INVALID_HID) */
  /* several MPI ranks writing one file (snapshot_write_ranks): this rank's
   * particles are rows [offset, offset + p->count) of total */
  int parallel;
  unsigned long long offset, total;
};

/** This process's MPI rank (0 without MPI). */
static int snapshot_rank(void) {
#ifdef SNAPSHOT_PARALLEL
  int r = 0, init = 0;
  MPI_Initialized(&init);
  if (init) MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
#else
  return 0;
#endif
}

/** Set when a file could not be closed after a failed write (disk full):
 *  HDF5 1.10 then crashes in its own exit handler, so the handler below,
 *  registered after HDF5's and therefore run before it, ends the process
 *  first.  error_exit has printed the message and removed the temporary
 *  files by then. */
static volatile int snapshot_poisoned = 0;

static void snapshot_atexit(void) {
  if (snapshot_poisoned) {
    fflush(NULL);
    _exit(1);
  }
}

/** Register snapshot_atexit once, after the HDF5 library has registered its
 *  own exit handler (at its initialisation). */
static void snapshot_register_atexit(void) {
  static int done = 0;
  if (!done) {
    H5open();
    atexit(snapshot_atexit);
    done = 1;
  }
}

/** Give up: close, remove the temporary file, print one line and exit. */
static void snapshot_fail(struct snapshot_writer *w, const char *what) __attribute__((noreturn));
static void snapshot_fail(struct snapshot_writer *w, const char *what) {
  const int err = errno;
  if (w->file >= 0) {
    /* close what is still open in the file: HDF5's exit handler would
     * otherwise crash on the objects of a file whose writes failed */
    const unsigned types = H5F_OBJ_DATASET | H5F_OBJ_GROUP | H5F_OBJ_DATATYPE | H5F_OBJ_ATTR;
    const ssize_t n = H5Fget_obj_count(w->file, types);
    if (n > 0) {
      hid_t *ids = error_malloc((size_t)n * sizeof *ids, "HDF5 object list");
      const ssize_t m = H5Fget_obj_ids(w->file, types, (size_t)n, ids);
      for (ssize_t i = 0; i < m; i++) {
        const H5I_type_t t = H5Iget_type(ids[i]);
        herr_t rc = 0; /* closing can fail too: nothing more to do then */
        if (t == H5I_ATTR) rc = H5Aclose(ids[i]);
        if (t == H5I_DATASET) rc = H5Dclose(ids[i]);
        if (t == H5I_GROUP) rc = H5Gclose(ids[i]);
        if (t == H5I_DATATYPE) rc = H5Tclose(ids[i]);
        (void)rc;
      }
      free(ids);
    }
    if (H5Fclose(w->file) < 0) snapshot_poisoned = 1;
  }
  w->file = H5I_INVALID_HID;
  unlink(w->tmp);
  error_unregister_tmpfile(w->tmp);
  error_exit("%s: cannot write %s (%s)", w->path, what,
             err ? strerror(err) : "HDF5 error: disk full or no permission?");
}

/** Check the result of an HDF5 call (negative = failure). */
#define SNAP_CHECK(w, call, what)             \
  do {                                        \
    errno = 0;                                \
    if ((call) < 0) snapshot_fail(w, (what)); \
  } while (0)

/** Write attribute `name` of n values of memory type `mtype` (file type
 *  `ftype`), as a 1-D array (SWIFT writes even scalars as arrays of 1). */
static void snapshot_attr(struct snapshot_writer *w, hid_t loc, const char *name, hid_t ftype,
                          hid_t mtype, int n, const void *data) {
  hsize_t dim = (hsize_t)n;
  hid_t space = H5Screate_simple(1, &dim, NULL);
  SNAP_CHECK(w, space, name);
  hid_t attr = H5Acreate2(loc, name, ftype, space, H5P_DEFAULT, H5P_DEFAULT);
  SNAP_CHECK(w, attr, name);
  SNAP_CHECK(w, H5Awrite(attr, mtype, data), name);
  H5Aclose(attr);
  H5Sclose(space);
}

static void snapshot_attr_double(struct snapshot_writer *w, hid_t loc, const char *name, int n,
                                 const double *v) {
  snapshot_attr(w, loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, n, v);
}

static void snapshot_attr_float1(struct snapshot_writer *w, hid_t loc, const char *name, float v) {
  snapshot_attr(w, loc, name, H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, 1, &v);
}

static void snapshot_attr_int1(struct snapshot_writer *w, hid_t loc, const char *name, int v) {
  snapshot_attr(w, loc, name, H5T_STD_I32LE, H5T_NATIVE_INT, 1, &v);
}

static void snapshot_attr_llong(struct snapshot_writer *w, hid_t loc, const char *name, int n,
                                const long long *v) {
  snapshot_attr(w, loc, name, H5T_STD_I64LE, H5T_NATIVE_LLONG, n, v);
}

/** A scalar fixed-length string attribute (what SWIFT writes, and what h5py
 *  and swiftsimio decode). */
static void snapshot_attr_string(struct snapshot_writer *w, hid_t loc, const char *name,
                                 const char *s) {
  if (!s) s = "";
  hid_t type = H5Tcopy(H5T_C_S1);
  SNAP_CHECK(w, type, name);
  SNAP_CHECK(w, H5Tset_size(type, strlen(s) > 0 ? strlen(s) : 1), name);
  SNAP_CHECK(w, H5Tset_strpad(type, H5T_STR_NULLTERM), name);
  hid_t space = H5Screate(H5S_SCALAR);
  SNAP_CHECK(w, space, name);
  hid_t attr = H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  SNAP_CHECK(w, attr, name);
  SNAP_CHECK(w, H5Awrite(attr, type, strlen(s) > 0 ? s : "\0"), name);
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
}

static hid_t snapshot_group(struct snapshot_writer *w, const char *name) {
  hid_t g = H5Gcreate2(w->file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  SNAP_CHECK(w, g, name);
  return g;
}

/** The five base units in cgs with SWIFT's attribute names (units.h). */
static void snapshot_units(struct snapshot_writer *w, const char *group,
                           const struct unit_system *us) {
  hid_t g = snapshot_group(w, group);
  snapshot_attr_double(w, g, "Unit mass in cgs (U_M)", 1, &us->mass_cgs);
  snapshot_attr_double(w, g, "Unit length in cgs (U_L)", 1, &us->length_cgs);
  snapshot_attr_double(w, g, "Unit time in cgs (U_t)", 1, &us->time_cgs);
  snapshot_attr_double(w, g, "Unit current in cgs (U_I)", 1, &us->current_cgs);
  snapshot_attr_double(w, g, "Unit temperature in cgs (U_T)", 1, &us->temperature_cgs);
  H5Gclose(g);
}

static void snapshot_header(struct snapshot_writer *w, const struct snapshot_meta *meta, size_t n) {
  hid_t g = snapshot_group(w, "/Header");
  const long long nl = (long long)(n & 0xffffffffULL), nh = (long long)(n >> 32);
  const long long this_file[6] = {(long long)n, 0, 0, 0, 0, 0};
  const long long total[6] = {nl, 0, 0, 0, 0, 0};
  const long long high[6] = {nh, 0, 0, 0, 0, 0};
  const double mass_table[6] = {0, 0, 0, 0, 0, 0};
  const double zero = 0, one = 1;
  snapshot_attr_double(w, g, "Time", 1, &meta->time);
  snapshot_attr_double(w, g, "BoxSize", 3, meta->box_size);
  snapshot_attr_llong(w, g, "NumPart_ThisFile", 6, this_file);
  snapshot_attr_llong(w, g, "NumPart_Total", 6, total);
  snapshot_attr_llong(w, g, "NumPart_Total_HighWord", 6, high);
  snapshot_attr_int1(w, g, "NumFilesPerSnapshot", 1);
  snapshot_attr_int1(w, g, "Dimension", 3);
  snapshot_attr_double(w, g, "MassTable", 6, mass_table);
  snapshot_attr_int1(w, g, "Flag_Entropy_ICs", 0);
  snapshot_attr_double(w, g, "Redshift", 1, &zero);
  snapshot_attr_double(w, g, "Scale-factor", 1, &one);
  snapshot_attr_string(w, g, "Code", "Bolide");
  snapshot_attr_string(w, g, "RunName", meta->run_name ? meta->run_name : "bolide");
  snapshot_attr_string(w, g, "OutputType", "FullVolume");
  snapshot_attr_string(w, g, "CodeVersion", PACKAGE_VERSION);
  snapshot_attr_string(w, g, "GitHash", BOLIDE_GIT_HASH);
  snapshot_attr_string(w, g, "Configuration", BOLIDE_CONFIGURE_ARGS);
  snapshot_attr_string(w, g, "Kernel", BOLIDE_KERNEL_NAME);
  H5Gclose(g);
}

/** /Parameters: the YAML text as one attribute, and each "key: value" line
 *  of a section as the attribute "Section:key" (SWIFT's layout).  Nested
 *  structures (Materials) are only in the whole text. */
static void snapshot_parameters(struct snapshot_writer *w, const char *text) {
  hid_t g = snapshot_group(w, "/Parameters");
  snapshot_attr_string(w, g, "UsedParametersYAML", text ? text : "");
  if (text) {
    char section[256] = "";
    const char *line = text;
    while (*line) {
      const char *end = strchr(line, '\n');
      size_t len = end ? (size_t)(end - line) : strlen(line);
      char buf[1024];
      if (len >= sizeof buf) len = sizeof buf - 1;
      memcpy(buf, line, len);
      buf[len] = '\0';
      char *hash = strchr(buf, '#');
      if (hash && !strchr(buf, '"') && !strchr(buf, '\'')) *hash = '\0';
      size_t l = strlen(buf);
      while (l > 0 && (buf[l - 1] == ' ' || buf[l - 1] == '\r')) buf[--l] = '\0';
      const char *colon = strchr(buf, ':');
      if (l > 0 && buf[0] != ' ' && buf[0] != '-' && colon && colon[1] == '\0') {
        /* "Section:" */
        snprintf(section, sizeof section, "%.*s", (int)(colon - buf), buf);
      } else if (l > 0 && buf[0] == ' ' && colon && section[0]) {
        /* "  key: value" one level down */
        const char *k = buf;
        while (*k == ' ') k++;
        const int indent = (int)(k - buf);
        const char *v = colon + 1;
        while (*v == ' ') v++;
        if (indent == 2 && *v && *k != '-') {
          char name[512];
          snprintf(name, sizeof name, "%s:%.*s", section, (int)(colon - k), k);
          if (H5Aexists(g, name) == 0) snapshot_attr_string(w, g, name, v);
        }
      } else if (l > 0 && buf[0] != ' ') {
        section[0] = '\0';
      }
      line = end ? end + 1 : line + strlen(line);
    }
  }
  H5Gclose(g);
}

/** The small metadata groups swiftsimio and SWIFT's tools look for. */
static void snapshot_metadata_groups(struct snapshot_writer *w, const struct snapshot_meta *meta) {
  hid_t g = snapshot_group(w, "/Code");
  snapshot_attr_string(w, g, "Code", "Bolide");
  snapshot_attr_string(w, g, "Code Version", PACKAGE_VERSION);
  snapshot_attr_string(w, g, "Git Revision", BOLIDE_GIT_HASH);
  snapshot_attr_string(w, g, "Configuration options", BOLIDE_CONFIGURE_ARGS);
  snapshot_attr_string(w, g, "Compiler", BOLIDE_CC_VERSION);
  snapshot_attr_string(w, g, "HDF5 library version", H5_VERSION);
  if (meta->command) snapshot_attr_string(w, g, "Command line", meta->command);
  H5Gclose(g);

  g = snapshot_group(w, "/Cosmology");
  snapshot_attr_int1(w, g, "Cosmological run", 0);
  H5Gclose(g);

  g = snapshot_group(w, "/Policy");
  snapshot_attr_int1(w, g, "hydro", meta->hydro);
  snapshot_attr_int1(w, g, "self gravity", meta->self_gravity);
  snapshot_attr_int1(w, g, "cosmological integration", 0);
  H5Gclose(g);

  g = snapshot_group(w, "/HydroScheme");
  snapshot_attr_string(w, g, "Scheme", "Bolide solid-body SPH");
  snapshot_attr_string(w, g, "Kernel function", BOLIDE_KERNEL_NAME);
  snapshot_attr_int1(w, g, "Dimension", 3);
  H5Gclose(g);

  g = snapshot_group(w, "/GravityScheme");
  H5Gclose(g);
  g = snapshot_group(w, "/SubgridScheme");
  H5Gclose(g);

  g = snapshot_group(w, "/RuntimePars");
  snapshot_attr_int1(w, g, "PeriodicBoundariesOn", meta->periodic ? 1 : 0);
  H5Gclose(g);
}

int snapshot_field_written(const struct part_field *f, int ic, int write_acc) {
  if (!f->h5name) return 0;
  if (ic) return (f->flags & (PART_IC_REQ | PART_IC_OPT)) != 0;
  return (f->flags & PART_SNAP) || (write_acc && (f->flags & PART_SNAP_ACC));
}

/** HDF5 memory and file types of a field's C type. */
static hid_t snapshot_mem_type(const struct part_field *f) {
  return f->type == PART_DOUBLE  ? H5T_NATIVE_DOUBLE
         : f->type == PART_INT64 ? H5T_NATIVE_INT64
                                 : H5T_NATIVE_INT32;
}
static hid_t snapshot_file_type(const struct part_field *f) {
  return f->type == PART_DOUBLE  ? H5T_IEEE_F64LE
         : f->type == PART_INT64 ? H5T_STD_I64LE
                                 : H5T_STD_I32LE;
}

/** The unit attributes of one dataset (SWIFT's names; swiftsimio reads the
 *  "U_x exponent" ones to build the unit, the others are for people). */
static void snapshot_dataset_attrs(struct snapshot_writer *w, hid_t d, const struct part_field *f,
                                   const struct unit_system *us, int compressed) {
  const double cgs = units_cgs_factor(us, f->uM, f->uL, f->uT);
  char expr[256];
  units_cgs_string(f->uM, f->uL, f->uT, expr, sizeof expr);
  snapshot_attr_float1(w, d, "U_M exponent", (float)f->uM);
  snapshot_attr_float1(w, d, "U_L exponent", (float)f->uL);
  snapshot_attr_float1(w, d, "U_t exponent", (float)f->uT);
  snapshot_attr_float1(w, d, "U_I exponent", 0.f);
  snapshot_attr_float1(w, d, "U_T exponent", 0.f);
  snapshot_attr_float1(w, d, "a-scale exponent", 0.f);
  snapshot_attr_float1(w, d, "h-scale exponent", 0.f);
  snapshot_attr_double(w, d, "Conversion factor to CGS (not including cosmological corrections)", 1,
                       &cgs);
  snapshot_attr_double(
      w, d, "Conversion factor to physical CGS (including cosmological corrections)", 1, &cgs);
  snapshot_attr_string(w, d, "Expression for physical CGS units", expr);
  snapshot_attr_string(w, d, "Description", f->description);
  snapshot_attr_int1(w, d, "Is Compressed", compressed);
  snapshot_attr_string(w, d, "Lossy compression filter", "None");
  snapshot_attr_int1(w, d, "Value stored as physical", 1);
  snapshot_attr_int1(w, d, "Property can be converted to comoving", 0);
}

/** One dataset: gather the ncomp component arrays starting at field k into
 *  an N x ncomp buffer and write it. */
static void snapshot_dataset(struct snapshot_writer *w, hid_t grp, int k, const struct parts *p,
                             const struct unit_system *us, int level) {
  const struct part_field *f = &part_fields[k];
  const size_t n = p->count, nc = (size_t)f->ncomp, s = f->size;
  char what[256];
  snprintf(what, sizeof what, "dataset /PartType0/%s", f->h5name);
  for (int c = 1; c < f->ncomp; c++)
    if (k + c >= part_nr_fields || !part_fields[k + c].h5name ||
        strcmp(part_fields[k + c].h5name, f->h5name) != 0 || part_fields[k + c].comp != c)
      error_bug("components of %s are not consecutive in BOLIDE_PART_FIELDS", f->h5name);

  char *buf = error_malloc((n ? n : 1) * nc * s, what);
  for (size_t c = 0; c < nc; c++) {
    const char *a = part_field_array(p, &part_fields[k + (int)c]);
    if (!a) /* (a field the run does not hold, parts_drop: zeros) */
      for (size_t i = 0; i < n; i++) memset(buf + (i * nc + c) * s, 0, s);
    else
      for (size_t i = 0; i < n; i++) memcpy(buf + (i * nc + c) * s, a + i * s, s);
  }

  /* the whole dataset: every rank's rows when several write it */
  const size_t N = w->parallel ? (size_t)w->total : n;
  hsize_t dims[2] = {N, nc};
  const int rank = nc > 1 ? 2 : 1;
  hid_t space = H5Screate_simple(rank, dims, NULL);
  SNAP_CHECK(w, space, what);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  SNAP_CHECK(w, dcpl, what);
  const int compressed = level > 0 && N > 0;
  if (compressed) {
    hsize_t chunk[2] = {N < 65536 ? N : 65536, nc};
    SNAP_CHECK(w, H5Pset_chunk(dcpl, rank, chunk), what);
    SNAP_CHECK(w, H5Pset_shuffle(dcpl), what);
    SNAP_CHECK(w, H5Pset_deflate(dcpl, (unsigned)level), what);
  }
  hid_t d =
      H5Dcreate2(grp, f->h5name, snapshot_file_type(f), space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  SNAP_CHECK(w, d, what);
  if (!w->parallel && n > 0)
    SNAP_CHECK(w, H5Dwrite(d, snapshot_mem_type(f), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf), what);
#ifdef SNAPSHOT_PARALLEL
  if (w->parallel && N > 0) {
    /* every rank its rows, collectively (compressed datasets need it) */
    hsize_t start[2] = {(hsize_t)w->offset, 0}, count[2] = {n, nc}, one[2] = {1, nc};
    hid_t mem = H5Screate_simple(rank, n > 0 ? count : one, NULL);
    SNAP_CHECK(w, mem, what);
    if (n > 0) {
      SNAP_CHECK(w, H5Sselect_hyperslab(space, H5S_SELECT_SET, start, NULL, count, NULL), what);
    } else {
      SNAP_CHECK(w, H5Sselect_none(space), what);
      SNAP_CHECK(w, H5Sselect_none(mem), what);
    }
    hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
    SNAP_CHECK(w, dxpl, what);
    SNAP_CHECK(w, H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE), what);
    SNAP_CHECK(w, H5Dwrite(d, snapshot_mem_type(f), mem, space, dxpl, buf), what);
    H5Pclose(dxpl);
    H5Sclose(mem);
  }
#endif
  snapshot_dataset_attrs(w, d, f, us, compressed);
  free(buf);
  H5Dclose(d);
  H5Pclose(dcpl);
  H5Sclose(space);
}

void snapshot_xdmf_name(const char *path, char *buf, size_t len) {
  const char *dot = strrchr(path, '.');
  const char *slash = strrchr(path, '/');
  size_t stem = strlen(path);
  if (dot && (!slash || dot > slash) && (strcmp(dot, ".hdf5") == 0 || strcmp(dot, ".h5") == 0))
    stem = (size_t)(dot - path);
  snprintf(buf, len, "%.*s.xmf", (int)stem, path);
}

/** Flush a file's data to disk (and, best effort, its folder's entry). */
static int snapshot_fsync(const char *path) {
  int fd = open(path, O_RDONLY);
  if (fd < 0) return -1;
  int rc = fsync(fd);
  close(fd);
  return rc;
}

static void snapshot_fsync_dir(const char *path) {
  char tmp[4096];
  snprintf(tmp, sizeof tmp, "%s", path);
  int fd = open(dirname(tmp), O_RDONLY | O_DIRECTORY);
  if (fd >= 0) {
    fsync(fd);
    close(fd);
  }
}

/** The XDMF description of the particle datasets (XDMF 2, read by
 *  ParaView's "XDMF Reader"): Polyvertex topology, XYZ geometry. */
static void snapshot_write_xdmf(const char *h5path, const struct snapshot_meta *meta, size_t n,
                                int write_acc) {
  char xmf[4096], tmp[4200];
  snapshot_xdmf_name(h5path, xmf, sizeof xmf);
  snprintf(tmp, sizeof tmp, "%s.tmp", xmf);
  const char *slash = strrchr(h5path, '/');
  const char *h5base = slash ? slash + 1 : h5path;

  error_register_tmpfile(tmp);
  FILE *f = fopen(tmp, "w");
  if (!f) error_exit("%s: cannot write: %s", tmp, strerror(errno));
  fprintf(f, "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n");
  fprintf(f, "<Xdmf Version=\"2.0\">\n <Domain>\n");
  fprintf(f, "  <Grid Name=\"PartType0\" GridType=\"Uniform\">\n");
  fprintf(f, "   <Time Value=\"%.17g\"/>\n", meta->time);
  fprintf(f, "   <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%zu\"/>\n", n);
  for (int k = 0; k < part_nr_fields; k++) {
    const struct part_field *fl = &part_fields[k];
    if (fl->comp != 0 || !snapshot_field_written(fl, meta->ic, write_acc)) continue;
    const int geometry = strcmp(fl->h5name, "Coordinates") == 0;
    const char *kind = fl->ncomp == 1   ? "Scalar"
                       : fl->ncomp == 3 ? "Vector"
                       : fl->ncomp == 6 ? "Tensor6"
                                        : "Matrix";
    if (geometry)
      fprintf(f, "   <Geometry GeometryType=\"XYZ\">\n");
    else
      fprintf(f, "   <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n", fl->h5name,
              kind);
    char dims[64];
    if (fl->ncomp > 1)
      snprintf(dims, sizeof dims, "%zu %d", n, fl->ncomp);
    else
      snprintf(dims, sizeof dims, "%zu", n);
    fprintf(f,
            "    <DataItem Dimensions=\"%s\" NumberType=\"%s\" Precision=\"%zu\" "
            "Format=\"HDF\">%s:/PartType0/%s</DataItem>\n",
            dims, fl->type == PART_DOUBLE ? "Float" : "Int", fl->size, h5base, fl->h5name);
    fprintf(f, geometry ? "   </Geometry>\n" : "   </Attribute>\n");
  }
  fprintf(f, "  </Grid>\n </Domain>\n</Xdmf>\n");
  if (ferror(f) | fflush(f) | fsync(fileno(f)) | fclose(f)) {
    unlink(tmp);
    error_exit("%s: cannot write (disk full?)", tmp);
  }
  if (rename(tmp, xmf) != 0) {
    unlink(tmp);
    error_exit("%s: cannot rename to %s: %s", tmp, xmf, strerror(errno));
  }
  error_unregister_tmpfile(tmp);
}

void snapshot_write_series(const char *dir, const char *basename, int count) {
  char path[4096], tmp[4200], xmf[4200];
  snprintf(path, sizeof path, "%s/%s.xmf", dir, basename);
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  error_register_tmpfile(tmp);
  FILE *f = fopen(tmp, "w");
  if (!f) error_exit("%s: cannot write: %s", tmp, strerror(errno));
  fprintf(f, "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n");
  fprintf(f, "<Xdmf Version=\"2.0\">\n <Domain>\n");
  fprintf(f, "  <Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n",
          basename);
  /* the Grid of every snapshot's own XDMF file, copied: one file that
   * ParaView opens as the time series of the run */
  for (int k = 0; k < count; k++) {
    snprintf(xmf, sizeof xmf, "%s/%s_%04d.xmf", dir, basename, k);
    FILE *in = fopen(xmf, "r");
    if (!in) continue; /* removed by the user: the series goes on without it */
    char line[1024];
    int inside = 0;
    while (fgets(line, sizeof line, in)) {
      if (strstr(line, "<Grid ")) inside = 1;
      if (inside) fprintf(f, "  %s", line);
      if (strstr(line, "</Grid>")) inside = 0;
    }
    fclose(in);
  }
  fprintf(f, "  </Grid>\n </Domain>\n</Xdmf>\n");
  if (ferror(f) | fclose(f)) {
    unlink(tmp);
    error_exit("%s: cannot write (disk full?)", tmp);
  }
  if (rename(tmp, path) != 0) {
    unlink(tmp);
    error_exit("%s: cannot rename to %s: %s", tmp, path, strerror(errno));
  }
  error_unregister_tmpfile(tmp);
}

/** snapshot_write, or with w->parallel set this rank's share of one file
 *  that every rank writes (snapshot_write_ranks). */
static void snapshot_write_impl(struct snapshot_writer *w, const struct snapshot_meta *meta,
                                const struct parts *p, const struct unit_system *us,
                                int write_acc) {
  const char *path = w->path;
  const int lead = !w->parallel || snapshot_rank() == 0;
  if (snprintf(w->tmp, sizeof w->tmp, "%s.tmp", path) >= (int)sizeof w->tmp)
    error_exit("%s: file name too long", path);
  if (meta->compression < 0 || meta->compression > 9)
    error_exit("%s: compression level %d out of range 0-9", path, meta->compression);
  if (meta->compression > 0 && H5Zfilter_avail(H5Z_FILTER_DEFLATE) <= 0)
    error_exit("%s: this HDF5 library has no gzip (deflate) filter", path);
  H5Eset_auto(H5E_DEFAULT, NULL, NULL);
  snapshot_register_atexit();

  /* create the file with open() first: the error message then says why */
  if (lead) {
    int fd = open(w->tmp, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) error_exit("%s: cannot create %s: %s", path, w->tmp, strerror(errno));
    close(fd);
    error_register_tmpfile(w->tmp);
  }
  /* H5F_CLOSE_STRONG: on a failure, closing the file also closes the groups
   * and datasets still open in it (otherwise HDF5's exit handler trips on
   * them after a failed write) */
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  SNAP_CHECK(w, fapl, "the file");
  SNAP_CHECK(w, H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG), "the file");
#ifdef SNAPSHOT_PARALLEL
  if (w->parallel) {
    MPI_Barrier(MPI_COMM_WORLD); /* (the file exists) */
    SNAP_CHECK(w, H5Pset_fapl_mpio(fapl, MPI_COMM_WORLD, MPI_INFO_NULL), "the file");
  }
#endif
  w->file = H5Fcreate(w->tmp, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  SNAP_CHECK(w, w->file, "the file");

  const size_t total = w->parallel ? (size_t)w->total : p->count;
  snapshot_header(w, meta, total);
  snapshot_units(w, "/Units", us);
  snapshot_units(w, "/InternalCodeUnits", us);
  snapshot_parameters(w, meta->params);
  snapshot_metadata_groups(w, meta);

  hid_t grp = snapshot_group(w, "/PartType0");
  for (int k = 0; k < part_nr_fields; k++)
    if (part_fields[k].comp == 0 && snapshot_field_written(&part_fields[k], meta->ic, write_acc))
      snapshot_dataset(w, grp, k, p, us, meta->compression);
  if (meta->ic) {
    /* SWIFT reads initial conditions under GADGET's singular names: hard
     * links make one file loadable by both codes (as woma's files are) */
    static const char *const alias[][2] = {{"SmoothingLengths", "SmoothingLength"},
                                           {"InternalEnergies", "InternalEnergy"},
                                           {"Densities", "Density"}};
    for (size_t a = 0; a < sizeof alias / sizeof alias[0]; a++)
      if (H5Lexists(grp, alias[a][0], H5P_DEFAULT) > 0)
        SNAP_CHECK(w, H5Lcreate_hard(grp, alias[a][0], grp, alias[a][1], H5P_DEFAULT, H5P_DEFAULT),
                   alias[a][1]);
  }
  SNAP_CHECK(w, H5Gclose(grp), "group /PartType0");

  errno = 0;
  const herr_t rc = H5Fclose(w->file);
  w->file = H5I_INVALID_HID;
  /* a close that failed to flush (disk full) leaves the file in HDF5's
   * list, and its exit handler then crashes on it (issue 18) */
  if (rc < 0) snapshot_poisoned = 1;
  if (rc < 0) snapshot_fail(w, "the file (closing)");
  if (!lead) return;
  if (snapshot_fsync(w->tmp) != 0) snapshot_fail(w, "the file (fsync)");
  if (rename(w->tmp, path) != 0) snapshot_fail(w, "the file (rename)");
  error_unregister_tmpfile(w->tmp);
  snapshot_write_xdmf(path, meta, total, write_acc);
  snapshot_fsync_dir(path);
}

void snapshot_write(const char *path, const struct snapshot_meta *meta, const struct parts *p,
                    const struct unit_system *us, int write_acc) {
  struct snapshot_writer w = {.path = path, .file = H5I_INVALID_HID};
  snapshot_write_impl(&w, meta, p, us, write_acc);
}

int snapshot_parallel(void) {
#ifdef SNAPSHOT_PARALLEL
  return 1;
#else
  return 0;
#endif
}

void snapshot_write_ranks(const char *path, const struct snapshot_meta *meta, const struct parts *p,
                          const struct unit_system *us, int write_acc) {
#ifdef SNAPSHOT_PARALLEL
  struct snapshot_writer w = {.path = path, .file = H5I_INVALID_HID, .parallel = 1};
  unsigned long long mine = p->count, before = 0, total = 0;
  MPI_Exscan(&mine, &before, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(&mine, &total, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (snapshot_rank() == 0) before = 0; /* (MPI_Exscan leaves rank 0's undefined) */
  w.offset = before;
  w.total = total;
  snapshot_write_impl(&w, meta, p, us, write_acc);
  MPI_Barrier(MPI_COMM_WORLD); /* (the file is complete and renamed) */
#else
  (void)path, (void)meta, (void)p, (void)us, (void)write_acc;
  error_bug("snapshot_write_ranks without parallel HDF5");
#endif
}
