-- Least-privilege roles for a site's bodyrec gallery on PostgreSQL (docs/postgresql.md).
-- Tested as written by src/bodyrec/store/gallery_server_test.cc (RolesFromTheDocs...).
--
-- Part 1, as a superuser, connected to the gallery's database (e.g. `createdb bodyrec_site` first):
--   bodyrec_admin  owns the gallery's tables: creates and upgrades the schema (`bodyrec gallery init`),
--                  and is the only role that may forget, purge and prune (it needs DELETE and, for the
--                  VACUUM FULL that scrubs erased rows, ownership of the tables).
--   bodyrec_sensor what `bodyrec reid` on a sensor needs: read the gallery, enrol users, store and
--                  replace scans, log events (and trim its own event history). No DELETE of users or
--                  scans: a sensor cannot erase anyone, so `reid --prune-unseen-for` is for the admin.
-- Give both a password in the server's authentication (ALTER ROLE ... PASSWORD, or certificates), and
-- put it on each machine in a password file (PGPASSFILE, mode 0600), never in the URI.
CREATE ROLE bodyrec_admin LOGIN;
CREATE ROLE bodyrec_sensor LOGIN;
-- CHECKPOINT after an erasure (lets the WAL that still holds erased rows be recycled sooner).
GRANT pg_checkpoint TO bodyrec_admin;
DO $$ BEGIN
  EXECUTE format('GRANT CONNECT ON DATABASE %I TO bodyrec_admin, bodyrec_sensor', current_database());
END $$;
GRANT USAGE, CREATE ON SCHEMA public TO bodyrec_admin;
GRANT USAGE ON SCHEMA public TO bodyrec_sensor;

-- Part 2, as bodyrec_admin after `bodyrec gallery --gallery postgresql://bodyrec_admin@HOST/DB init`
-- (the tables exist then). A gallery made before schema 4 gets table event_spools when the admin first
-- opens it with this bodyrec: run the last GRANT then (until it is run, a sensor's reid --events warns
-- that the gallery does not list its spool, and goes on).
GRANT SELECT ON bodyrec_gallery TO bodyrec_sensor;
GRANT SELECT, UPDATE ON gallery_state TO bodyrec_sensor;
GRANT SELECT, INSERT, UPDATE ON users, scans TO bodyrec_sensor;
GRANT SELECT, INSERT, DELETE ON events TO bodyrec_sensor;
GRANT USAGE ON SEQUENCE users_id_seq, scans_id_seq, events_id_seq TO bodyrec_sensor;
-- reid --events lists its event spool, so that forget, purge and prune scrub it (schema 4); DELETE takes a
-- spool whose file is gone off the list (gallery spools --scrub): it names files, not people.
GRANT SELECT, INSERT, UPDATE, DELETE ON event_spools TO bodyrec_sensor;
